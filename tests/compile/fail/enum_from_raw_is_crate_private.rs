use lafert_smartris::types::BaudRate;

fn main() {
    let _ = BaudRate::from_raw(96);
}
