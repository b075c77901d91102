//! The EULUMDAT writers. Every field is listed once, in file order, with the width the
//! format description gives it; the exact writer prints each number as the shortest text
//! that reads back as the same value, the standard writer fits every field into its width
//! (what other lighting programs expect, and what `ldt convert` writes by default).

use super::eulumdat::Eulumdat;
use super::text::exact;

/// What one field holds.
#[derive(Debug, Clone, Copy)]
pub enum FieldValue<'a> {
    /// Free text (names, numbers of reports, lamp types).
    Text(&'a str),
    /// A count, written in full (a count cannot be rounded).
    Count(i64),
    /// A measured or declared number.
    Number(f64),
}

/// One line of an EULUMDAT file.
#[derive(Debug, Clone)]
pub struct LdtField<'a> {
    /// The field as the format description names it (`"line 9 (luminaire name)"`).
    pub name: String,
    /// The most characters the format allows.
    pub width: usize,
    /// Its content.
    pub value: FieldValue<'a>,
}

/// A file written to EULUMDAT's fixed widths, with what had to be shortened.
#[derive(Debug, Clone)]
pub struct StandardLdt {
    /// The file's text (CRLF line ends).
    pub text: String,
    /// One note per text cut to its width or count longer than its width.
    pub notes: Vec<String>,
}

/// Why a file cannot be written to EULUMDAT's widths without changing what it says.
#[derive(Debug, Clone, PartialEq)]
pub struct NotStandard {
    /// The field (or "the written file").
    pub field: String,
    /// What is wrong.
    pub reason: String,
}

impl std::fmt::Display for NotStandard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {}; write with `exact` to keep every digit (other programs may not read \
             such a file)",
            self.field, self.reason
        )
    }
}

impl std::error::Error for NotStandard {}

/// Field widths of the format description (lines 1–29; every intensity has 6).
mod width {
    pub const TEXT: usize = 78;
    pub const ITYP: usize = 1;
    pub const ISYM: usize = 1;
    pub const COUNT_OF_ANGLES: usize = 2;
    pub const STEP: usize = 5;
    pub const FILE_NAME: usize = 8;
    pub const DIMENSION: usize = 4;
    pub const FACTOR: usize = 6;
    pub const LAMP_COUNT: usize = 4;
    pub const LAMP_TYPE: usize = 24;
    pub const LAMP_FLUX: usize = 12;
    pub const COLOUR: usize = 16;
    pub const CRI: usize = 6;
    pub const WATTS: usize = 8;
    pub const DIRECT_RATIO: usize = 7;
    pub const ANGLE: usize = 6;
    pub const INTENSITY: usize = 6;
}

impl Eulumdat {
    /// Every line of the file in order, with its name and width.
    pub fn ldt_fields(&self) -> Vec<LdtField<'_>> {
        use FieldValue::{Count, Number, Text};
        let d = &self.dimensions;
        let mut out = FieldList(Vec::new());
        let mut add =
            |line: &str, what: &str, width: usize, value| out.add(line, what, width, value);
        add("1", "company", width::TEXT, Text(&self.company));
        add("2", "Ityp", width::ITYP, Count(self.ityp.into()));
        add("3", "Isym", width::ISYM, Count(self.symmetry.isym().into()));
        add("4", "Mc", width::COUNT_OF_ANGLES, Count(self.mc() as i64));
        add("5", "Dc", width::STEP, Number(self.dc));
        add("6", "Ng", width::COUNT_OF_ANGLES, Count(self.ng() as i64));
        add("7", "Dg", width::STEP, Number(self.dg));
        add(
            "8",
            "measurement report",
            width::TEXT,
            Text(&self.report_number),
        );
        add(
            "9",
            "luminaire name",
            width::TEXT,
            Text(&self.luminaire_name),
        );
        add(
            "10",
            "luminaire number",
            width::TEXT,
            Text(&self.luminaire_number),
        );
        add("11", "file name", width::FILE_NAME, Text(&self.file_name));
        add("12", "date/user", width::TEXT, Text(&self.date_user));
        let dims = [
            ("13", "length", d.length),
            ("14", "width", d.width),
            ("15", "height", d.height),
            ("16", "luminous length", d.area_length),
            ("17", "luminous width", d.area_width),
            ("18", "luminous height C0", d.area_heights[0]),
            ("19", "luminous height C90", d.area_heights[1]),
            ("20", "luminous height C180", d.area_heights[2]),
            ("21", "luminous height C270", d.area_heights[3]),
            ("22", "DFF", self.dff_percent),
            ("23", "LORL", self.lorl_percent),
        ];
        for (line, what, v) in dims {
            add(line, what, width::DIMENSION, Number(v));
        }
        add(
            "24",
            "conversion factor",
            width::FACTOR,
            Number(self.conversion_factor),
        );
        add("25", "tilt", width::FACTOR, Number(self.tilt_deg));
        add(
            "26",
            "lamp sets",
            width::LAMP_COUNT,
            Count(self.lamp_sets.len() as i64),
        );
        for (i, s) in self.lamp_sets.iter().enumerate() {
            let set = |what: &str| format!("set {} {what}", i + 1);
            add(
                "26a",
                &set("lamps"),
                width::LAMP_COUNT,
                Count(s.count.into()),
            );
            add(
                "26b",
                &set("lamp type"),
                width::LAMP_TYPE,
                Text(&s.lamp_type),
            );
            add("26c", &set("flux"), width::LAMP_FLUX, Number(s.flux_lm));
            add("26d", &set("colour"), width::COLOUR, Text(&s.color));
            add("26e", &set("CRI"), width::CRI, Text(&s.cri));
            add("26f", &set("watts"), width::WATTS, Number(s.watts));
        }
        for (i, v) in self.direct_ratios.iter().enumerate() {
            let what = format!("direct ratio {}", i + 1);
            add("27", &what, width::DIRECT_RATIO, Number(*v));
        }
        for c in &self.c_angles {
            add("28", &format!("C {}", exact(*c)), width::ANGLE, Number(*c));
        }
        for g in &self.gamma_angles {
            add("29", &format!("γ {}", exact(*g)), width::ANGLE, Number(*g));
        }
        for (k, row) in self
            .stored_plane_indices()
            .into_iter()
            .zip(&self.intensities)
        {
            let c = self.c_angles[k];
            for (g, v) in self.gamma_angles.iter().zip(row) {
                let what = format!("intensity C{} γ{}", exact(c), exact(*g));
                add("30", &what, width::INTENSITY, Number(*v));
            }
        }
        out.0
    }

    /// Writes the file in EULUMDAT format (CRLF line ends, numbers printed exactly, text
    /// as stored): reads back as the same data, but may not fit the format's widths.
    pub fn to_ldt_string(&self) -> String {
        let lines = self.ldt_fields().into_iter().map(|f| match f.value {
            FieldValue::Text(s) => s.to_string(),
            FieldValue::Count(n) => n.to_string(),
            FieldValue::Number(v) => exact(v),
        });
        join_crlf(lines)
    }

    /// Writes the file to EULUMDAT's fixed widths: numbers rounded to the most decimals
    /// their field holds, text cut to its width (with a note). Refuses a number that no
    /// rounding fits (an intensity of a million cd/klm or more, a luminaire of 10 m or more)
    /// and a file that would not read back (angles closer than the written precision).
    pub fn to_ldt_standard(&self) -> Result<StandardLdt, NotStandard> {
        let mut notes = Vec::new();
        let mut lines = Vec::new();
        for f in self.ldt_fields() {
            let line = match f.value {
                FieldValue::Text(s) => {
                    let n = s.chars().count();
                    if n > f.width {
                        notes.push(format!(
                            "{}: {n} characters cut to EULUMDAT's {}",
                            f.name, f.width
                        ));
                    }
                    s.chars().take(f.width).collect()
                }
                FieldValue::Count(n) => {
                    let s = n.to_string();
                    if s.len() > f.width {
                        notes.push(format!(
                            "{} = {s} is longer than EULUMDAT's {} characters; written in full",
                            f.name, f.width
                        ));
                    }
                    s
                }
                FieldValue::Number(v) => fit_number(v, f.width).ok_or_else(|| NotStandard {
                    field: f.name.clone(),
                    reason: format!(
                        "{} does not fit EULUMDAT's {} characters",
                        exact(v),
                        f.width
                    ),
                })?,
            };
            lines.push(line);
        }
        let text = join_crlf(lines.into_iter());
        if let Err(e) = Eulumdat::parse("the written file", text.as_bytes()) {
            return Err(NotStandard {
                field: "the file rounded to EULUMDAT's widths".to_string(),
                reason: format!("it would not read back ({e})"),
            });
        }
        Ok(StandardLdt { text, notes })
    }
}

/// The fields collected in file order.
struct FieldList<'a>(Vec<LdtField<'a>>);

impl<'a> FieldList<'a> {
    fn add(&mut self, line: &str, what: &str, width: usize, value: FieldValue<'a>) {
        self.0.push(LdtField {
            name: format!("line {line} ({what})"),
            width,
            value,
        });
    }
}

fn join_crlf(lines: impl Iterator<Item = String>) -> String {
    let mut out = String::new();
    for l in lines {
        out.push_str(&l);
        out.push_str("\r\n");
    }
    out
}

/// `v` with as many decimals as `width` characters hold (trailing zeros dropped), or
/// `None` when even the whole number is wider.
pub fn fit_number(v: f64, width: usize) -> Option<String> {
    if !v.is_finite() {
        return None;
    }
    for decimals in (0..width.saturating_sub(1)).rev() {
        let mut s = format!("{v:.decimals$}");
        if s.contains('.') {
            let trimmed = s.trim_end_matches('0').trim_end_matches('.').len();
            s.truncate(trimmed);
        }
        if s == "-0" {
            s = "0".to_string();
        }
        if s.len() <= width {
            return Some(s);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::fit_number;

    #[test]
    fn numbers_fit_their_width_with_the_most_decimals() {
        assert_eq!(fit_number(903.4996780611565, 6).as_deref(), Some("903.5"));
        assert_eq!(fit_number(12.345678, 6).as_deref(), Some("12.346"));
        assert_eq!(fit_number(123456.7, 6).as_deref(), Some("123457"));
        assert_eq!(fit_number(1234567.0, 6), None);
        assert_eq!(fit_number(0.000_01, 6).as_deref(), Some("0"));
        assert_eq!(fit_number(-0.000_01, 6).as_deref(), Some("0"));
        assert_eq!(fit_number(22.5, 5).as_deref(), Some("22.5"));
        assert_eq!(fit_number(1219.2, 4).as_deref(), Some("1219"));
        assert_eq!(fit_number(-12.6, 4).as_deref(), Some("-13"));
        assert_eq!(fit_number(f64::NAN, 6), None);
    }
}
