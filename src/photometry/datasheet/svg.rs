//! The datasheet as one SVG page: title, summary beside the polar diagram, the cartesian
//! and isocandela diagrams side by side, then the UGR and luminance tables, warnings and
//! the footer. The diagrams are nested `<svg>` elements scaled from their own size.

use std::fmt::Write as _;

use super::{escape, Sheet, Table};

/// Page width and margin, SVG units (pixels at 96 dpi).
const PAGE: f64 = 1100.0;
const MARGIN: f64 = 30.0;
/// Width of a diagram on the page (two side by side).
const DIAGRAM: f64 = 515.0;

/// Lays the page out top to bottom.
struct Page {
    body: String,
    y: f64,
}

impl Page {
    fn text(&mut self, x: f64, y: f64, size: f64, style: &str, s: &str) {
        let _ = write!(
            self.body,
            "<text x=\"{x:.1}\" y=\"{y:.1}\" font-size=\"{size}\" {style}>{}</text>",
            escape(s)
        );
    }

    /// A diagram (an SVG document) scaled to `DIAGRAM` wide at (x, y); returns its height.
    fn diagram(&mut self, svg: &str, x: f64, y: f64) -> f64 {
        let (w, h) = svg_size(svg).unwrap_or((1100.0, 860.0));
        let height = DIAGRAM * h / w;
        let inner = svg
            .find('>')
            .map(|end| &svg[end + 1..])
            .unwrap_or(svg)
            .trim_end();
        let inner = inner.strip_suffix("</svg>").unwrap_or(inner);
        let _ = write!(
            self.body,
            "<svg x=\"{x:.1}\" y=\"{y:.1}\" width=\"{DIAGRAM}\" height=\"{height:.1}\" viewBox=\"0 0 {w} {h}\">{inner}</svg>"
        );
        height
    }

    fn heading(&mut self, s: &str) {
        self.y += 34.0;
        self.text(MARGIN, self.y, 18.0, "font-weight=\"bold\"", s);
        self.y += 8.0;
    }

    fn note(&mut self, s: &str) {
        self.y += 18.0;
        self.text(MARGIN, self.y, 12.0, "fill=\"#666\"", s);
    }

    /// A table: row labels in the first column, values right-aligned in equal columns.
    fn table(&mut self, t: &Table) {
        const ROW: f64 = 17.0;
        const LABEL: f64 = 90.0;
        let columns = t.header.len().saturating_sub(1).max(1);
        // Columns as wide as their longest text (7 units a character at 11), at least 80.
        let longest = t
            .header
            .iter()
            .chain(t.rows.iter().flatten())
            .skip(1)
            .map(|c| c.chars().count())
            .max()
            .unwrap_or(0);
        let cell = ((PAGE - 2.0 * MARGIN - LABEL) / columns as f64)
            .min((7.0 * longest as f64 + 14.0).max(80.0));
        let right = |k: usize| MARGIN + LABEL + cell * (k + 1) as f64 - 4.0;
        let bold = "font-weight=\"bold\"";
        self.y += 6.0;
        if !t.groups.is_empty() {
            self.y += ROW;
            let mut first = 0;
            for (label, span) in &t.groups {
                let mid = MARGIN + LABEL + cell * (first as f64 + *span as f64 / 2.0);
                self.text(
                    mid,
                    self.y,
                    12.0,
                    "text-anchor=\"middle\" font-weight=\"bold\"",
                    label,
                );
                first += span;
            }
        }
        self.y += ROW;
        self.rule(self.y + 5.0, "#999");
        self.text(MARGIN, self.y, 11.0, bold, &t.header[0]);
        for (k, h) in t.header.iter().skip(1).enumerate() {
            let style = "text-anchor=\"end\" font-weight=\"bold\"";
            self.text(right(k), self.y, 11.0, style, h);
        }
        for row in &t.rows {
            self.y += ROW;
            self.text(MARGIN, self.y, 11.0, "", &row[0]);
            for (k, v) in row.iter().skip(1).enumerate() {
                self.text(right(k), self.y, 11.0, "text-anchor=\"end\"", v);
            }
            self.rule(self.y + 5.0, "#e2e2e2");
        }
    }

    fn rule(&mut self, y: f64, colour: &str) {
        let _ = write!(
            self.body,
            "<line x1=\"{MARGIN}\" x2=\"{:.1}\" y1=\"{y:.1}\" y2=\"{y:.1}\" stroke=\"{colour}\"/>",
            PAGE - MARGIN
        );
    }
}

/// The `width` and `height` of an SVG document's root element.
fn svg_size(svg: &str) -> Option<(f64, f64)> {
    let tag = &svg[svg.find("<svg")?..];
    let tag = &tag[..tag.find('>')?];
    let attr = |name: &str| -> Option<f64> {
        let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        tag[start..].split('"').next()?.parse().ok()
    };
    Some((attr("width")?, attr("height")?))
}

/// The sheet as one SVG document.
pub fn svg(sheet: &Sheet) -> String {
    let mut page = Page {
        body: String::new(),
        y: 0.0,
    };
    page.text(MARGIN, 48.0, 26.0, "", &sheet.name);
    page.text(MARGIN, 72.0, 14.0, "fill=\"#666\"", &sheet.subtitle);
    let top = 92.0;
    // Summary at the left, the polar diagram at the right.
    let mut y = top;
    for (label, value) in &sheet.summary {
        y += 19.0;
        page.text(MARGIN, y, 13.0, "font-weight=\"bold\"", label);
        let lines = crate::io::wrap_words(value, 46);
        for (k, line) in lines.iter().enumerate() {
            page.text(MARGIN + 190.0, y + 16.0 * k as f64, 13.0, "", line);
        }
        y += 16.0 * lines.len().saturating_sub(1) as f64;
    }
    let mut diagrams = sheet.diagrams.iter();
    let right = PAGE - MARGIN - DIAGRAM;
    let polar = diagrams.next().map_or(0.0, |d| page.diagram(d, right, top));
    page.y = (y + 10.0).max(top + polar);
    // The others two by two.
    let rest: Vec<&String> = diagrams.collect();
    for pair in rest.chunks(2) {
        let mut tallest: f64 = 0.0;
        for (k, d) in pair.iter().enumerate() {
            let x = if k == 0 { MARGIN } else { right };
            tallest = tallest.max(page.diagram(d, x, page.y + 10.0));
        }
        page.y += 10.0 + tallest;
    }
    for section in &sheet.sections {
        page.heading(&section.heading);
        if let Some(note) = &section.note {
            page.note(note);
        }
        match &section.table {
            Ok(t) => page.table(t),
            Err(why) => page.note(why),
        }
    }
    if !sheet.warnings.is_empty() {
        page.heading("Warnings");
        for w in &sheet.warnings {
            for line in crate::io::wrap_words(w, 150) {
                page.note(&line);
            }
        }
    }
    page.y += 36.0;
    page.text(MARGIN, page.y, 11.0, "fill=\"#777\"", &sheet.footer);
    let height = (page.y + MARGIN).ceil();
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{PAGE}\" height=\"{height}\" viewBox=\"0 0 {PAGE} {height}\" font-family=\"sans-serif\"><rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>{}</svg>\n",
        page.body
    )
}

#[cfg(test)]
mod tests {
    use super::svg_size;

    #[test]
    fn reads_the_root_size_and_wraps_words() {
        let doc =
            "<svg width=\"1100\" height=\"860\" viewBox=\"0 0 1100 860\" xmlns=\"x\"><g/></svg>";
        assert_eq!(svg_size(doc), Some((1100.0, 860.0)));
        assert_eq!(crate::io::wrap_words("aa bb cc", 5), vec!["aa bb", "cc"]);
    }
}
