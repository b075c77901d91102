//! Text handling shared by the EULUMDAT and IES readers: byte decoding (BOM, UTF-8 or
//! Windows-1252), line splitting (CRLF/LF/CR) and number parsing with comma decimals.

use super::error::ParseError;

/// A decoded photometric file: its lines (without terminators) and the warnings that
/// decoding produced.
#[derive(Debug, Clone)]
pub struct SourceText {
    /// The name used in messages (usually the path as given).
    pub name: String,
    /// Lines of the file, 1-based line `n` is `lines[n - 1]`.
    pub lines: Vec<String>,
    /// Things that were accepted but deserve a note (encoding, BOM, …).
    pub warnings: Vec<String>,
}

impl SourceText {
    /// Decodes `bytes`: a UTF-8 BOM is skipped, valid UTF-8 is taken as is, anything else
    /// is read as Windows-1252 (the encoding of most European luminaire files).
    pub fn decode(name: &str, bytes: &[u8]) -> SourceText {
        let mut warnings = Vec::new();
        let body = match bytes.strip_prefix(b"\xEF\xBB\xBF") {
            Some(rest) => {
                warnings.push("UTF-8 byte-order mark skipped".to_string());
                rest
            }
            None => bytes,
        };
        let text = match std::str::from_utf8(body) {
            Ok(s) => s.to_string(),
            Err(_) => {
                warnings.push("text is not UTF-8: read as Windows-1252".to_string());
                let (cow, _, _) = encoding_rs::WINDOWS_1252.decode(body);
                cow.into_owned()
            }
        };
        let mut lines: Vec<String> = text
            .split('\n')
            .map(|l| l.strip_suffix('\r').unwrap_or(l).to_string())
            .collect();
        // A final terminator leaves one empty element: that is not a line.
        if lines.last().is_some_and(|l| l.is_empty()) {
            lines.pop();
        }
        // Old Mac files use bare CR.
        if lines.len() == 1 && lines[0].contains('\r') {
            lines = lines[0].split('\r').map(str::to_string).collect();
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

/// Parses one number, accepting a comma as the decimal separator. Returns whether a comma
/// was used so callers can warn once. Rejects NaN and infinities.
pub fn parse_number(token: &str) -> Option<(f64, bool)> {
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

/// A number read from the file, with the line it came from.
#[derive(Debug, Clone, Copy)]
pub struct Token {
    /// The value.
    pub value: f64,
    /// 1-based line number.
    pub line: usize,
}

/// Reads whitespace-separated numbers across lines, starting at a given line.
pub struct NumberStream<'a> {
    src: &'a SourceText,
    line: usize,
    pending: std::collections::VecDeque<&'a str>,
    separators: &'static [char],
    /// Set when any number used a decimal comma.
    pub saw_comma: bool,
}

impl<'a> NumberStream<'a> {
    /// Starts reading at 1-based `line`. `separators` split tokens within a line
    /// (whitespace always does).
    pub fn new(src: &'a SourceText, line: usize, separators: &'static [char]) -> Self {
        NumberStream {
            src,
            line: line.saturating_sub(1),
            pending: Default::default(),
            separators,
            saw_comma: false,
        }
    }

    /// The 1-based line the next token comes from (or the last line read).
    pub fn line(&self) -> usize {
        self.line.max(1)
    }

    fn fill(&mut self) -> bool {
        while self.pending.is_empty() {
            if self.line >= self.src.lines.len() {
                return false;
            }
            let text = self.src.lines[self.line].as_str();
            self.line += 1;
            let seps = self.separators;
            self.pending.extend(
                text.split(|ch: char| ch.is_whitespace() || seps.contains(&ch))
                    .filter(|t| !t.is_empty()),
            );
        }
        true
    }

    /// The next number; `what` names it in the error.
    pub fn next(&mut self, what: &str) -> Result<Token, ParseError> {
        if !self.fill() {
            return Err(self.src.error(
                self.src.lines.len() + 1,
                format!("unexpected end of file: expected {what}"),
            ));
        }
        let tok = self.pending.pop_front().expect("filled");
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

    /// Reads `n` numbers.
    pub fn take(&mut self, n: usize, what: &str) -> Result<Vec<Token>, ParseError> {
        (0..n).map(|_| self.next(what)).collect()
    }

    /// The first line at or after the stream position holding anything but whitespace,
    /// if any is left.
    pub fn remaining_content_line(&mut self) -> Option<usize> {
        if self.fill() {
            Some(self.line)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let t = SourceText::decode("x", b"\xEF\xBB\xBFa\r\nb\r\n");
        assert_eq!(t.lines, vec!["a", "b"]);
        assert_eq!(t.warnings.len(), 1);
        let t = SourceText::decode("x", b"Lumin\xe4r\n");
        assert_eq!(t.lines, vec!["Luminär"]);
        assert!(t.warnings[0].contains("Windows-1252"));
        let t = SourceText::decode("x", b"a\rb\rc");
        assert_eq!(t.lines, vec!["a", "b", "c"]);
    }
}
