//! What a benchmark shows: lines and Markdown tables for people, or its JSON document for
//! scripts. Every `bench` command builds one [`BenchReport`] here, in the library (the
//! ratios and percentages included); the command prints [`BenchReport::text`].

/// A Markdown table: a header and rows of cells, each column left- or right-aligned.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    header: Vec<String>,
    right: Vec<bool>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column names, every column left-aligned.
    pub fn new(header: &[&str]) -> Table {
        Table {
            header: header.iter().map(|h| h.to_string()).collect(),
            right: vec![false; header.len()],
            rows: Vec::new(),
        }
    }

    /// The columns from `first` on right-aligned (numbers).
    pub fn numbers_from(mut self, first: usize) -> Table {
        for r in self.right.iter_mut().skip(first) {
            *r = true;
        }
        self
    }

    /// Adds a row (as many cells as columns; fewer are padded with empty cells).
    pub fn row(&mut self, cells: Vec<String>) {
        debug_assert!(cells.len() <= self.header.len(), "{cells:?}");
        self.rows.push(cells);
    }

    /// The rows added.
    pub fn rows(&self) -> &[Vec<String>] {
        &self.rows
    }

    /// The table as Markdown (a header line, the alignment line, one line per row).
    pub fn markdown(&self) -> String {
        let line = |cells: &[String]| {
            let mut s = String::from("|");
            for k in 0..self.header.len() {
                s.push(' ');
                s.push_str(cells.get(k).map_or("", String::as_str));
                s.push_str(" |");
            }
            s
        };
        let rule: String = self
            .right
            .iter()
            .map(|&r| if r { "---:|" } else { "---|" })
            .collect();
        let mut out = vec![line(&self.header), format!("|{rule}")];
        out.extend(self.rows.iter().map(|r| line(r)));
        out.join("\n")
    }
}

/// One part of a report.
#[derive(Debug, Clone, PartialEq)]
enum Block {
    Line(String),
    Table(Table),
}

/// A benchmark's result: what people read (lines and tables) and what scripts read (JSON).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BenchReport {
    blocks: Vec<Block>,
    json: serde_json::Value,
}

impl BenchReport {
    /// A report whose JSON document is `json` (the rows and what they were measured on).
    pub fn new(json: serde_json::Value) -> BenchReport {
        BenchReport {
            blocks: Vec::new(),
            json,
        }
    }

    /// Adds a line of text.
    pub fn line(&mut self, text: impl Into<String>) {
        self.blocks.push(Block::Line(text.into()));
    }

    /// Adds a table.
    pub fn table(&mut self, table: Table) {
        self.blocks.push(Block::Table(table));
    }

    /// The tables, in order.
    pub fn tables(&self) -> impl Iterator<Item = &Table> {
        self.blocks.iter().filter_map(|b| match b {
            Block::Table(t) => Some(t),
            Block::Line(_) => None,
        })
    }

    /// The JSON document.
    pub fn json(&self) -> &serde_json::Value {
        &self.json
    }

    /// The lines and tables as Markdown.
    pub fn markdown(&self) -> String {
        let parts: Vec<String> = self
            .blocks
            .iter()
            .map(|b| match b {
                Block::Line(l) => l.clone(),
                Block::Table(t) => t.markdown(),
            })
            .collect();
        parts.join("\n")
    }

    /// What the command prints: the JSON document on one line, or the Markdown.
    pub fn text(&self, as_json: bool) -> String {
        if as_json {
            self.json.to_string()
        } else {
            self.markdown()
        }
    }
}

/// `v` with `digits` decimals, or `none` when there is no value.
pub fn or_none(v: Option<f64>, digits: usize, none: &str) -> String {
    v.map_or(none.to_string(), |v| format!("{v:.digits$}"))
}

/// A solver's phases for people: "select 0.12, piece powers 0.01, …", seconds with
/// `digits` decimals.
pub fn phase_list(t: &crate::radiosity::gpu::ShotTimes, digits: usize) -> String {
    [
        ("select", t.select),
        ("piece powers", t.piece_powers),
        ("plan", t.plan),
        ("gather", t.gather),
        ("links", t.links),
        ("cull", t.cull),
        ("record", t.record),
        ("batch wait", t.batch_wait),
        ("catch-up", t.catch_up),
    ]
    .iter()
    .map(|(name, s)| format!("{name} {s:.digits$}"))
    .collect::<Vec<_>>()
    .join(", ")
}

#[cfg(test)]
mod tests {
    use super::{BenchReport, Table};

    #[test]
    fn a_report_prints_markdown_with_aligned_columns_or_its_json() {
        let mut t = Table::new(&["model", "triangles", "s"]).numbers_from(1);
        t.row(vec!["box".into(), "12".into(), "0.50".into()]);
        t.row(vec!["hall".into(), "3 000".into()]);
        let mut r = BenchReport::new(serde_json::json!({ "rows": [1, 2] }));
        r.line("heading");
        r.table(t);
        r.line("note");
        assert_eq!(
            r.text(false),
            "heading\n| model | triangles | s |\n|---|---:|---:|\n| box | 12 | 0.50 |\n| hall | 3 000 |  |\nnote"
        );
        assert_eq!(r.text(true), r#"{"rows":[1,2]}"#);
        assert_eq!(r.tables().count(), 1);
    }
}
