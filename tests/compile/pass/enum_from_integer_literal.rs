use lafert_smartris::types::BaudRate;

fn main() {
    let _: Result<BaudRate, _> = BaudRate::try_from(96u16);
}
