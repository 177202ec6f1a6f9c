//! Description data types are the runtime's own ([`drivebus::DataType`]); what the IR adds is
//! how they serialize inside their owner.

pub use drivebus_model::DataType;

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;

    #[test]
    fn strings_serialize_their_capacity_beside_the_type() {
        #[derive(Serialize)]
        struct Owner {
            #[serde(flatten)]
            data_type: DataType,
        }
        let json = |data_type| serde_json::to_string(&Owner { data_type }).unwrap();
        assert_eq!(
            json(DataType::String(16)),
            r#"{"type":"string","length":16}"#
        );
        assert_eq!(json(DataType::Unsigned(2)), r#"{"type":"u16"}"#);
    }
}
