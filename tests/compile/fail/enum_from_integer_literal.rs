use lafert_smartris::types::BaudRate;

fn main() {
    // The field is private: an arbitrary number is not a baud rate.
    let _ = BaudRate(96);
}
