//! Tables of numbers written as CSV at full precision.

use crate::error::PlotError;

/// Named columns of f64 values. A non-finite value is written as an empty cell (the quantity is not
/// defined there).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with these column names.
    #[must_use]
    pub fn new(columns: Vec<String>) -> Self {
        Self {
            columns,
            rows: Vec::new(),
        }
    }

    /// Appends a row; `Err` if its length differs from the number of columns.
    pub fn push(&mut self, row: Vec<f64>) -> Result<(), PlotError> {
        if row.len() != self.columns.len() {
            return Err(PlotError::RowLength {
                expected: self.columns.len(),
                found: row.len(),
            });
        }
        self.rows.push(row);
        Ok(())
    }

    /// The column names.
    #[must_use]
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// The rows.
    #[must_use]
    pub fn rows(&self) -> &[Vec<f64>] {
        &self.rows
    }

    /// The table as CSV: a header line, then one line per row. Values are written with Rust's
    /// shortest representation that reads back to the same f64 (`{:?}`), so nothing is rounded.
    pub fn to_csv(&self) -> Result<String, PlotError> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        let io = |e: csv::Error| PlotError::Render(e.to_string());
        writer.write_record(&self.columns).map_err(io)?;
        for row in &self.rows {
            writer
                .write_record(row.iter().map(|v| {
                    if v.is_finite() {
                        format!("{v:?}")
                    } else {
                        String::new()
                    }
                }))
                .map_err(io)?;
        }
        let bytes = writer
            .into_inner()
            .map_err(|e| PlotError::Render(e.to_string()))?;
        String::from_utf8(bytes).map_err(|e| PlotError::Render(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip_and_gaps_are_empty() {
        let mut t = Table::new(vec!["z".into(), "error, max".into()]);
        t.push(vec![0.1, 1.0 / 3.0]).unwrap();
        t.push(vec![1e-300, f64::NAN]).unwrap();
        assert!(t.push(vec![1.0]).is_err());
        let csv = t.to_csv().unwrap();
        assert_eq!(csv, "z,\"error, max\"\n0.1,0.3333333333333333\n1e-300,\n");
        let third: f64 = "0.3333333333333333".parse().unwrap();
        assert_eq!(third, 1.0 / 3.0);
    }
}
