//! Tables (`table_sdaster`): named, typed columns with possibly empty cells.

use crate::diag::{Error, Result};

#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Empty,
    Int(i64),
    Real(f64),
    Text(String),
}

impl Cell {
    pub fn is_empty(&self) -> bool {
        matches!(self, Cell::Empty)
    }
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Cell::Int(i) => Some(*i as f64),
            Cell::Real(r) => Some(*r),
            _ => None,
        }
    }
}

/// Column type as Code_Aster names it: I, R, or K8/K16/K24/K32/K80.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColType {
    I,
    R,
    K(usize),
}

impl ColType {
    pub fn name(self) -> String {
        match self {
            ColType::I => "I".into(),
            ColType::R => "R".into(),
            ColType::K(n) => format!("K{n}"),
        }
    }
    pub fn parse(s: &str) -> Option<ColType> {
        match s.trim() {
            "I" => Some(ColType::I),
            "R" => Some(ColType::R),
            k => k.strip_prefix('K').and_then(|n| n.parse().ok()).map(ColType::K),
        }
    }
    /// The text type wide enough for `s` (K8, K16, K24, K32, K80).
    pub fn text_for(len: usize) -> ColType {
        ColType::K([8, 16, 24, 32, 80].into_iter().find(|&n| len <= n).unwrap_or(80))
    }
}

#[derive(Debug, Clone)]
pub struct Column {
    pub name: String,
    pub ty: ColType,
    pub cells: Vec<Cell>,
}

#[derive(Debug, Clone, Default)]
pub struct Table {
    pub title: String,
    pub columns: Vec<Column>,
}

impl Table {
    pub fn nrows(&self) -> usize {
        self.columns.first().map(|c| c.cells.len()).unwrap_or(0)
    }

    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c.name == name)
    }

    pub fn require_column(&self, name: &str, table: &str) -> Result<usize> {
        self.column(name).ok_or_else(|| {
            let names: Vec<&str> = self.columns.iter().map(|c| c.name.as_str()).collect();
            Error::runtime(format!("table {table} has no parameter '{name}' (parameters: {})", names.join(", ")))
        })
    }

    /// Append a column, padding or checking its length against the table.
    pub fn add_column(&mut self, name: &str, ty: ColType, mut cells: Vec<Cell>) -> Result<()> {
        if self.column(name).is_some() {
            return Err(Error::runtime(format!("the table already has a parameter '{name}'")));
        }
        let n = self.nrows();
        if self.columns.is_empty() {
            // First column fixes the row count.
        } else if cells.len() < n {
            cells.resize(n, Cell::Empty);
        } else if cells.len() > n {
            for c in &mut self.columns {
                c.cells.resize(cells.len(), Cell::Empty);
            }
        }
        self.columns.push(Column { name: name.into(), ty, cells });
        Ok(())
    }

    /// Keep only the rows whose index is in `rows` (in that order).
    pub fn select_rows(&self, rows: &[usize]) -> Table {
        Table {
            title: self.title.clone(),
            columns: self
                .columns
                .iter()
                .map(|c| Column {
                    name: c.name.clone(),
                    ty: c.ty,
                    cells: rows.iter().map(|&r| c.cells[r].clone()).collect(),
                })
                .collect(),
        }
    }

    /// Widen a text column so that `len` characters fit.
    pub fn widen(&mut self, col: usize, len: usize) {
        if let ColType::K(n) = self.columns[col].ty {
            if len > n {
                self.columns[col].ty = ColType::text_for(len);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_padded_to_the_table_length() {
        let mut t = Table::default();
        t.add_column("A", ColType::I, vec![Cell::Int(1), Cell::Int(2)]).unwrap();
        t.add_column("B", ColType::R, vec![Cell::Real(0.5)]).unwrap();
        assert_eq!(t.nrows(), 2);
        assert_eq!(t.columns[1].cells[1], Cell::Empty);
        t.add_column("C", ColType::K(8), vec![Cell::Text("x".into()); 3]).unwrap();
        assert_eq!(t.nrows(), 3);
        assert!(t.add_column("A", ColType::I, vec![]).is_err());
        assert_eq!(ColType::text_for(17), ColType::K(24));
    }
}
