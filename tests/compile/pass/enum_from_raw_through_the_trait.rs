use drivebus::parameter::OpenEnum;
use lafert_smartris::types::BaudRate;

fn main() {
    let _ = <BaudRate as OpenEnum>::raw(BaudRate::try_from(96).unwrap());
}
