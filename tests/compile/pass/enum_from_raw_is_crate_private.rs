use lafert_smartris::types::BaudRate;

fn main() {
    let _ = BaudRate::VALUES[0].raw();
}
