// The codec's `OpenEnum::from_raw` takes a proof only drivebus can make: no way around `TryFrom`.
use drivebus::parameter::{FromWire, OpenEnum};
use lafert_smartris::types::BaudRate;

fn main() {
    let _ = <BaudRate as OpenEnum>::from_raw(96, FromWire(()));
}
