//! A datasheet as text and SVG diagrams ([`Sheet`]), gathered once by `ldt report` and
//! laid out as HTML or SVG.

pub(super) use crate::io::xml_escape as escape;

/// One table of the sheet, as text (each renderer escapes it).
pub(super) struct Table {
    /// An optional first header row of (label, columns spanned), after the row labels.
    pub groups: Vec<(String, usize)>,
    /// The header row (the first cell heads the row labels).
    pub header: Vec<String>,
    /// The rows: a label, then the values.
    pub rows: Vec<Vec<String>>,
}

/// A titled part of the sheet: a note and a table, or why there is none.
pub(super) struct Section {
    /// The heading.
    pub heading: String,
    /// A line under the heading.
    pub note: Option<String>,
    /// The table, or the reason it is missing.
    pub table: Result<Table, String>,
}

/// Everything a datasheet shows, as text and SVG diagrams, ready for HTML or SVG.
pub(super) struct Sheet {
    /// The luminaire's name (the file's when it has none).
    pub name: String,
    /// Company and file name.
    pub subtitle: String,
    /// The summary rows (label, value).
    pub summary: Vec<(String, String)>,
    /// The polar, cartesian and isocandela diagrams, as SVG documents.
    pub diagrams: Vec<String>,
    /// The UGR and luminance tables.
    pub sections: Vec<Section>,
    /// The file's warnings.
    pub warnings: Vec<String>,
    /// The last line: tool, version, units, conditions.
    pub footer: String,
}
