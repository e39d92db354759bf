//! Reading back the CSV files the command line writes (`shape`): RFC 4180 quoting, one record
//! a line (the writer puts no newline inside a field).

use std::path::Path;

/// Fields of one CSV line.
pub fn fields(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted, mut chars) = (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// A CSV file: its header and its rows, each as long as the header.
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Parse `text`; panics (failing the test) on an empty text or a row whose length differs
    /// from the header's.
    pub fn parse(text: &str) -> Self {
        let mut lines = text.lines();
        let header = fields(lines.next().unwrap_or_else(|| panic!("empty CSV")));
        let rows: Vec<Vec<String>> = lines.map(fields).collect();
        for row in &rows {
            assert_eq!(row.len(), header.len(), "row {row:?} against header {header:?}");
        }
        Table { header, rows }
    }

    /// Read and parse the file at `path`.
    pub fn read(path: &Path) -> Self {
        Self::parse(&std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
    }

    /// The index of the column `name`; panics naming it when there is none.
    pub fn col(&self, name: &str) -> usize {
        self.header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name} in {:?}", self.header))
    }

    /// The row whose `file` column ends with `file`; panics when there is none.
    pub fn row_of(&self, file: &str) -> &[String] {
        let c = self.col("file");
        self.rows.iter().find(|r| r[c].ends_with(file)).unwrap_or_else(|| panic!("no row for {file}"))
    }

    /// The `column` of the row of `file`.
    pub fn get(&self, file: &str, column: &str) -> &str {
        &self.row_of(file)[self.col(column)]
    }
}
