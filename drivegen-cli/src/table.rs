//! Aligned text tables for people.

use std::fmt::{self, Write as _};
use std::io;

/// Formats rows (the first is the header) with columns padded to their widest cell.
pub fn render(rows: &[Vec<String>]) -> String {
    let mut table = Table::default();
    for row in rows {
        table.row(row.iter().map(|cell| cell as &dyn fmt::Display));
    }
    let mut out = Vec::new();
    // Writing to a Vec cannot fail, and the cells are the rows' text.
    let _ = table.write(&mut out);
    String::from_utf8_lossy(&out).into_owned()
}

/// A table built row by row, each cell formatted once into one buffer: a capture of millions
/// of frames (`decode`) costs no allocation per cell.
#[derive(Debug, Default)]
pub struct Table {
    text: String,
    /// The end of each cell in `text`.
    cells: Vec<usize>,
    /// The end of each row in `cells`.
    rows: Vec<usize>,
    /// Each column's widest cell, in characters.
    widths: Vec<usize>,
}

impl Table {
    /// Adds a row.
    pub fn row<'c>(&mut self, cells: impl IntoIterator<Item = &'c dyn fmt::Display>) {
        for (column, cell) in cells.into_iter().enumerate() {
            let start = self.text.len();
            // Writing to a String cannot fail.
            let _ = write!(self.text, "{cell}");
            let width = self.text[start..].chars().count();
            match self.widths.get_mut(column) {
                Some(widest) => *widest = (*widest).max(width),
                None => self.widths.push(width),
            }
            self.cells.push(self.text.len());
        }
        self.rows.push(self.cells.len());
    }

    /// Writes the rows, columns padded to their widest cell, two spaces apart, each line's
    /// trailing blanks trimmed.
    pub fn write(&self, out: &mut impl io::Write) -> io::Result<()> {
        let mut line = String::new();
        let (mut cell, mut start) = (0, 0);
        for &row_end in &self.rows {
            line.clear();
            for column in 0..row_end - cell {
                let end = self.cells[cell + column];
                let text = &self.text[start..end];
                start = end;
                if column > 0 {
                    line.push_str("  ");
                }
                line.push_str(text);
                let pad = self.widths[column].saturating_sub(text.chars().count());
                line.extend(std::iter::repeat_n(' ', pad));
            }
            cell = row_end;
            out.write_all(line.trim_end().as_bytes())?;
            out.write_all(b"\n")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn columns_line_up() {
        let rows = vec![
            vec!["name".to_string(), "value".to_string()],
            vec!["bus_dc_link".to_string(), "49.50 V".to_string()],
        ];
        assert_eq!(
            super::render(&rows),
            "name         value\nbus_dc_link  49.50 V\n"
        );
    }
}
