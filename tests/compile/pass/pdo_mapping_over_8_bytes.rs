use drivebus::canopen::pdo::{MappedObject, PdoLayout};

const TPDO: PdoLayout<2> = PdoLayout::new([MappedObject::new(0x6064, 0, 32); 2]);

fn main() {
    let _ = TPDO.len();
}
