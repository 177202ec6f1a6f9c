//! Work on several drives at once, a scoped thread each (network boot, reads through the
//! CANopen network manager).

/// `work` on every item at once, a thread each; the results in the items' order (`Err` for a
/// thread that panicked).
pub fn at_once<T: Send, R: Send>(
    items: impl IntoIterator<Item = T>,
    work: impl Fn(T) -> R + Sync,
) -> Vec<std::thread::Result<R>> {
    let work = &work;
    std::thread::scope(|scope| {
        let running: Vec<_> = items
            .into_iter()
            .map(|item| scope.spawn(move || work(item)))
            .collect();
        running.into_iter().map(|thread| thread.join()).collect()
    })
}
