use drivebus::canopen::pdo::{MappedObject, PdoLayout};

// Three 32-bit objects need 12 bytes; a PDO carries 8.
const TPDO: PdoLayout<3> = PdoLayout::new([MappedObject::new(0x6064, 0, 32); 3]);

fn main() {
    let _ = TPDO.len();
}
