//! Text handling shared by the EULUMDAT and IES readers: byte decoding (BOM, UTF-8 or
//! Windows-1252), line splitting (CRLF/LF/CR) and number parsing with comma decimals.

use std::borrow::Cow;

use super::error::ParseError;

/// Decodes `bytes`: a UTF-8 BOM is skipped, valid UTF-8 is borrowed as is, anything else
/// is read as Windows-1252 (the encoding of most European luminaire files). Returns the
/// text and the warnings decoding produced.
pub fn decode_text(bytes: &[u8]) -> (Cow<'_, str>, Vec<String>) {
    let mut warnings = Vec::new();
    let body = match bytes.strip_prefix(b"\xEF\xBB\xBF") {
        Some(rest) => {
            warnings.push("UTF-8 byte-order mark skipped".to_string());
            rest
        }
        None => bytes,
    };
    let text = match std::str::from_utf8(body) {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => {
            warnings.push("text is not UTF-8: read as Windows-1252".to_string());
            let (cow, _, _) = encoding_rs::WINDOWS_1252.decode(body);
            Cow::Owned(cow.into_owned())
        }
    };
    (text, warnings)
}

/// A decoded photometric file split into lines, with the warnings decoding produced.
#[derive(Debug, Clone)]
pub struct SourceText<'t> {
    /// The name used in messages (usually the path as given).
    pub name: String,
    /// Lines of the file without terminators: 1-based line `n` is `lines[n - 1]`.
    pub lines: Vec<&'t str>,
    /// Things that were accepted but deserve a note (encoding, BOM, …).
    pub warnings: Vec<String>,
}

impl<'t> SourceText<'t> {
    /// Splits decoded `text` into lines (LF, CRLF or bare CR).
    pub fn new(name: &str, text: &'t str, warnings: Vec<String>) -> SourceText<'t> {
        let bytes = text.as_bytes();
        let sep =
            if memchr::memchr(b'\n', bytes).is_none() && memchr::memchr(b'\r', bytes).is_some() {
                b'\r'
            } else {
                b'\n'
            };
        let mut lines = Vec::with_capacity(bytes.len() / 8 + 1);
        let mut start = 0;
        for end in memchr::memchr_iter(sep, bytes).chain(std::iter::once(bytes.len())) {
            // Splitting at an ASCII byte keeps UTF-8 boundaries.
            let line = &text[start..end];
            lines.push(line.strip_suffix('\r').unwrap_or(line));
            start = end + 1;
        }
        // A final terminator leaves one empty element: that is not a line.
        if lines.last().is_some_and(|l| l.is_empty()) {
            lines.pop();
        }
        SourceText {
            name: name.to_string(),
            lines,
            warnings,
        }
    }

    /// An error at 1-based `line` of this file.
    pub fn error(&self, line: usize, message: impl Into<String>) -> ParseError {
        ParseError::new(&self.name, line, message)
    }
}

/// Clinger's fast path for a plain decimal at the start of `b` (sign, digits, one dot):
/// with at most 18 digits, a mantissa within 53 bits and a scale of at most 10²² the
/// value is one correctly rounded division, exactly what `str::parse` gives. Returns the
/// value and the number of bytes read; `None` when the slow path must decide.
fn fast_decimal_prefix(b: &[u8]) -> Option<(f64, usize)> {
    const POW10: [f64; 23] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
        1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
    ];
    let (neg, mut i) = match b.first()? {
        b'-' => (true, 1),
        b'+' => (false, 1),
        _ => (false, 0),
    };
    let (mut mant, mut count, mut frac, mut dot) = (0u64, 0usize, 0usize, false);
    while let Some(&c) = b.get(i) {
        match c {
            b'0'..=b'9' => {
                count += 1;
                if count > 18 {
                    return None;
                }
                mant = mant * 10 + u64::from(c - b'0');
                frac += usize::from(dot);
            }
            b'.' if !dot => dot = true,
            _ => break,
        }
        i += 1;
    }
    if count == 0 || mant > (1 << 53) || frac > 22 {
        return None;
    }
    let v = mant as f64 / POW10[frac];
    Some((if neg { -v } else { v }, i))
}

/// [`fast_decimal_prefix`] of a whole token.
fn fast_decimal(b: &[u8]) -> Option<f64> {
    match fast_decimal_prefix(b) {
        Some((v, n)) if n == b.len() => Some(v),
        _ => None,
    }
}

/// Parses one number, accepting a comma as the decimal separator. Returns whether a comma
/// was used so callers can warn once. Rejects NaN and infinities.
pub fn parse_number(token: &str) -> Option<(f64, bool)> {
    if let Some(v) = fast_decimal(token.as_bytes()) {
        return Some((v, false));
    }
    let t = token.trim();
    if t.is_empty() {
        return None;
    }
    let comma = t.contains(',');
    let value: f64 = if comma {
        if t.matches(',').count() > 1 || t.contains('.') {
            return None;
        }
        t.replace(',', ".").parse().ok()?
    } else {
        t.parse().ok()?
    };
    // Rust accepts "inf" and "NaN"; photometric data never legitimately contains them.
    if !value.is_finite()
        || t.chars()
            .any(|ch| ch.is_ascii_alphabetic() && ch != 'e' && ch != 'E')
    {
        return None;
    }
    Some((value, comma))
}

/// A number for a message: plain when it is of ordinary size, in exponent form when plain
/// digits would run to dozens of characters (1e300, 4.9e-324).
pub fn show(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-6..1e12).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A computed number for a message (a mean, a difference: not a value the file holds,
/// which [`show`] echoes whole), to four significant digits: 15.29, 0.6792, 1170; in
/// exponent form where [`show`] uses it.
pub fn show_rounded(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if !(1e-6..1e12).contains(&a) {
        return format!("{v:.3e}");
    }
    let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// The shortest decimal text that reads back as exactly `v`, in exponent form outside
/// 1e-5…1e15 so that no value needs hundreds of digits (what the writers print).
pub fn exact(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-5..1e15).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A number read from the file, with the line it came from.
#[derive(Debug, Clone, Copy)]
pub struct Token {
    /// The value.
    pub value: f64,
    /// 1-based line number.
    pub line: usize,
}

/// Reads whitespace-separated numbers across lines, starting at a given line.
pub struct NumberStream<'a, 't> {
    src: &'a SourceText<'t>,
    /// Lines consumed so far (the current line is `line`, 1-based).
    line: usize,
    rest: &'t str,
    separators: &'static [char],
    /// Set when any number used a decimal comma.
    pub saw_comma: bool,
}

impl<'a, 't> NumberStream<'a, 't> {
    /// Starts reading at 1-based `line`. `separators` split tokens within a line
    /// (whitespace always does).
    pub fn new(src: &'a SourceText<'t>, line: usize, separators: &'static [char]) -> Self {
        NumberStream {
            src,
            line: line.saturating_sub(1),
            rest: "",
            separators,
            saw_comma: false,
        }
    }

    /// The 1-based line the last token came from.
    pub fn line(&self) -> usize {
        self.line.max(1)
    }

    fn is_sep(&self, ch: char) -> bool {
        ch.is_whitespace() || self.separators.contains(&ch)
    }

    /// Byte offset of the first separator in `s` (`skip_seps` false) or of the first
    /// non-separator (`skip_seps` true); bytes while ASCII, chars after that.
    fn scan(&self, s: &str, skip_seps: bool) -> usize {
        for (i, &b) in s.as_bytes().iter().enumerate() {
            if !b.is_ascii() {
                return i + s[i..]
                    .find(|ch| self.is_sep(ch) != skip_seps)
                    .unwrap_or(s.len() - i);
            }
            let sep = b.is_ascii_whitespace() || self.separators.contains(&(b as char));
            if sep != skip_seps {
                return i;
            }
        }
        s.len()
    }

    /// Moves to the next token; false at the end of the file.
    fn fill(&mut self) -> bool {
        loop {
            let trimmed = &self.rest[self.scan(self.rest, true)..];
            if !trimmed.is_empty() {
                self.rest = trimmed;
                return true;
            }
            if self.line >= self.src.lines.len() {
                self.rest = "";
                return false;
            }
            self.rest = self.src.lines[self.line];
            self.line += 1;
        }
    }

    /// The next number; `what` names it in the error.
    pub fn next(&mut self, what: &str) -> Result<Token, ParseError> {
        if !self.fill() {
            return Err(self.src.error(
                self.src.lines.len() + 1,
                format!("unexpected end of file: expected {what}"),
            ));
        }
        let bytes = self.rest.as_bytes();
        if let Some((value, n)) = fast_decimal_prefix(bytes) {
            let ends = bytes.get(n).is_none_or(|&b| {
                b.is_ascii_whitespace() || (b == b',' && self.separators.contains(&','))
            });
            if ends {
                self.rest = &self.rest[n..];
                return Ok(Token {
                    value,
                    line: self.line,
                });
            }
        }
        let end = self.scan(self.rest, false);
        let (tok, rest) = self.rest.split_at(end);
        self.rest = rest;
        let line = self.line;
        match parse_number(tok) {
            Some((value, comma)) => {
                self.saw_comma |= comma;
                Ok(Token { value, line })
            }
            None => Err(self
                .src
                .error(line, format!("expected {what}, found {tok:?}"))),
        }
    }

    /// The next field of a line-oriented format: `None` for a blank line met where a
    /// value should start (an empty field), otherwise the next number.
    pub fn next_or_blank(&mut self, what: &str) -> Result<Option<Token>, ParseError> {
        if self.rest.trim().is_empty() {
            if let Some(line) = self.src.lines.get(self.line) {
                if line.trim().is_empty() {
                    self.line += 1;
                    self.rest = "";
                    return Ok(None);
                }
            }
        }
        self.next(what).map(Some)
    }

    /// Everything after the last value read, if anything is left: where it starts and
    /// what it is. Consumes the stream.
    pub fn trailing(&mut self) -> Option<Trailing> {
        let first_line = self.remaining_content_line()?;
        let mut t = Trailing {
            first_line,
            numbers: 0,
            end_markers: 0,
            other: 0,
        };
        while self.fill() {
            let end = self.scan(self.rest, false);
            let (tok, rest) = self.rest.split_at(end);
            if parse_number(tok).is_some() {
                t.numbers += 1;
            } else if is_end_marker(tok) {
                t.end_markers += 1;
            } else {
                t.other += 1;
            }
            self.rest = rest;
        }
        Some(t)
    }

    /// Reads `n` numbers.
    pub fn take(&mut self, n: usize, what: &str) -> Result<Vec<Token>, ParseError> {
        (0..n).map(|_| self.next(what)).collect()
    }

    /// The line of the next token, if any is left.
    pub fn remaining_content_line(&mut self) -> Option<usize> {
        if self.fill() {
            Some(self.line)
        } else {
            None
        }
    }
}

/// What follows a table: see [`NumberStream::trailing`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Trailing {
    /// 1-based line of the first token after the table.
    pub first_line: usize,
    /// Tokens that are numbers (more data than the header announced).
    pub numbers: usize,
    /// `END` lines and `^Z` bytes.
    pub end_markers: usize,
    /// Anything else.
    pub other: usize,
}

impl Trailing {
    /// "N values", "an END marker", … for messages.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if self.numbers > 0 {
            parts.push(format!("{} value(s)", self.numbers));
        }
        if self.end_markers > 0 {
            parts.push(format!("{} end marker(s) (END, ^Z)", self.end_markers));
        }
        if self.other > 0 {
            parts.push(format!("{} other word(s)", self.other));
        }
        parts.join(" and ")
    }
}

/// True for the end markers real files carry after their table: `END` lines and the
/// DOS end-of-file byte (`^Z`).
pub fn is_end_marker(token: &str) -> bool {
    token.eq_ignore_ascii_case("END") || token.chars().all(|c| c == '\u{1a}')
}

/// Angles must lie in `range` and increase strictly; `what` names them in errors
/// ("C", "γ", "vertical", …).
pub fn check_increasing(
    src: &SourceText<'_>,
    tokens: &[Token],
    range: impl std::ops::RangeBounds<f64> + std::fmt::Debug,
    what: &str,
) -> Result<(), ParseError> {
    for (i, t) in tokens.iter().enumerate() {
        if !range.contains(&t.value) {
            return Err(src.error(
                t.line,
                format!("{what} angle {} outside {range:?} degrees", t.value),
            ));
        }
        if i > 0 && t.value <= tokens[i - 1].value {
            return Err(src.error(
                t.line,
                format!(
                    "{what} angles must increase: {} follows {}",
                    t.value,
                    tokens[i - 1].value
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computed_numbers_in_messages_have_four_significant_digits() {
        let cases = [
            (15.293770556118483, "15.29"),
            (1170.2902442075372, "1170"),
            (0.6791824957591521, "0.6792"),
            (4.039627764049243, "4.04"),
            (9.99996, "10"),
            (-2.5, "-2.5"),
            (0.0, "0"),
            (123456.7, "123457"),
            (1.5e-9, "1.500e-9"),
        ];
        for (v, text) in cases {
            assert_eq!(show_rounded(v), text, "{v}");
        }
    }

    #[test]
    fn numbers_with_comma_and_rejects() {
        assert_eq!(parse_number("1,5"), Some((1.5, true)));
        assert_eq!(parse_number(" 2.25 "), Some((2.25, false)));
        assert_eq!(parse_number("1e3"), Some((1000.0, false)));
        assert_eq!(parse_number("NaN"), None);
        assert_eq!(parse_number("inf"), None);
        assert_eq!(parse_number("1,2,3"), None);
        assert_eq!(parse_number("abc"), None);
        assert_eq!(parse_number(""), None);
    }

    #[test]
    fn decode_handles_bom_crlf_and_cp1252() {
        let split = |b: &[u8]| {
            let (text, w) = decode_text(b);
            let lines: Vec<String> = SourceText::new("x", &text, vec![])
                .lines
                .iter()
                .map(|s| s.to_string())
                .collect();
            (lines, w)
        };
        let (lines, w) = split(b"\xEF\xBB\xBFa\r\nb\r\n");
        assert_eq!(lines, vec!["a", "b"]);
        assert_eq!(w.len(), 1);
        let (lines, w) = split(b"Lumin\xe4r\n");
        assert_eq!(lines, vec!["Luminär"]);
        assert!(w[0].contains("Windows-1252"));
        let (lines, _) = split(b"a\rb\rc");
        assert_eq!(lines, vec!["a", "b", "c"]);
    }

    #[test]
    fn fast_path_agrees_with_std_parse() {
        for t in [
            "0",
            "1.0000",
            "-0.5",
            "444.70",
            "0.00001",
            "1234567890123456",
            "2445.4",
            "+3.25",
            ".",
        ] {
            assert_eq!(fast_decimal(t.as_bytes()), t.parse::<f64>().ok(), "{t}");
        }
        assert_eq!(fast_decimal(b"1e3"), None);
        assert_eq!(fast_decimal(b"1234567890123456789"), None);
    }
}
