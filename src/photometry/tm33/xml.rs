//! The XML dialects: ATLA S001 (`<ATLA_S001_A>`), TM-33-23 (`<IESTM33-22>`) and
//! eulumdat-rs's `<LuminaireOpticalData>`. Elements are found by local name (namespaces
//! ignored); every error names the element and its line.

use roxmltree::{Document, Node};

use super::{grid_from_points, number, Dialect, Emitter, Header, Intensity, Opening, Tm33};
use crate::photometry::error::ParseError;
use crate::photometry::spectral::Spectrum;

/// One XML document being read.
struct Reader<'a> {
    name: &'a str,
    /// Byte offsets where lines 2, 3, … begin (for line numbers in messages).
    line_starts: Vec<usize>,
}

/// Reads an XML document.
pub(super) fn read(name: &str, text: &str, warnings: &mut Vec<String>) -> Result<Tm33, ParseError> {
    let doc = Document::parse(text).map_err(|e| {
        let pos = e.pos();
        ParseError::new(name, pos.row as usize, format!("not well-formed XML: {e}"))
    })?;
    let r = Reader {
        name,
        line_starts: text
            .bytes()
            .enumerate()
            .filter(|(_, b)| *b == b'\n')
            .map(|(i, _)| i + 1)
            .collect(),
    };
    let root = doc.root_element();
    let tag = root.tag_name().name();
    let dialect = if tag.starts_with("ATLA_S001") {
        Dialect::AtlaXml
    } else if tag.starts_with("IESTM33") {
        Dialect::Tm33Xml
    } else if tag == "LuminaireOpticalData" {
        Dialect::OpticalDataXml
    } else {
        return Err(r.error(
            root,
            format!("root element <{tag}> is not a TM-33 or ATLA document (expected <IESTM33-22>, <ATLA_S001_A> or <LuminaireOpticalData>)"),
        ));
    };
    let header = child(root, &["Header"])
        .map(|h| r.header(h))
        .unwrap_or_default();
    let dimensions_m = match child(root, &["Luminaire"]).and_then(|l| child(l, &["Dimensions"])) {
        Some(d) => r.dimensions(d)?,
        None => [0.0; 3],
    };
    let gonio_type = descendant(root, &["Gonioradiometer", "Goniometer"])
        .and_then(|g| child(g, &["Type", "GoniometerType"]))
        .map(|t| (t, element_text(t)));
    let emitters = root
        .children()
        .filter(|n| n.is_element() && n.tag_name().name() == "Emitter")
        .map(|e| r.emitter(e, gonio_type.clone()))
        .collect::<Result<Vec<_>, _>>()?;
    for faces in root
        .descendants()
        .filter(|n| n.tag_name().name() == "EmissionAreas")
    {
        for face in faces.children().filter(|n| n.is_element()) {
            let tag = face.tag_name().name();
            if tag != "BottomFace" {
                warnings.push(format!(
                    "line {}: EmissionAreas/{tag} is not read (only the bottom face's openings are)",
                    r.line(face)
                ));
            }
        }
    }
    Ok(Tm33 {
        dialect,
        header,
        dimensions_m,
        emitters,
    })
}

impl Reader<'_> {
    /// The 1-based line where `node` begins.
    fn line(&self, node: Node) -> usize {
        1 + self
            .line_starts
            .partition_point(|&s| s <= node.range().start)
    }

    fn error(&self, node: Node, message: impl Into<String>) -> ParseError {
        ParseError::new(self.name, self.line(node), message)
    }

    /// The number in element `names` under `parent`, if the element is there.
    fn number(&self, parent: Node, names: &[&str]) -> Result<Option<f64>, ParseError> {
        child(parent, names)
            .map(|n| {
                number(
                    self.name,
                    self.line(n),
                    n.tag_name().name(),
                    &element_text(n),
                )
            })
            .transpose()
    }

    fn header(&self, h: Node) -> Header {
        Header::from_lookup(|names| child(h, names).map(element_text).unwrap_or_default())
    }

    fn dimensions(&self, d: Node) -> Result<[f64; 3], ParseError> {
        let mut out = [0.0; 3];
        for (k, names) in [
            ["Length", "Diameter"],
            ["Width", "Width"],
            ["Height", "Height"],
        ]
        .iter()
        .enumerate()
        {
            if let Some(v) = self.number(d, names)? {
                if !(0.0..=1e5).contains(&v) {
                    let n = child(d, names).expect("just read");
                    return Err(self.error(n, format!("{}: {v} is not a size", names[0])));
                }
                out[k] = v;
            }
        }
        Ok(out)
    }

    fn emitter(&self, e: Node, gonio_type: Option<(Node, String)>) -> Result<Emitter, ParseError> {
        let quantity = match self.number(e, &["Quantity"])? {
            None => 1,
            Some(q) if (1.0..=1e6).contains(&q) && q.fract() == 0.0 => q as u32,
            Some(q) => {
                let n = child(e, &["Quantity"]).expect("just read");
                return Err(self.error(n, format!("Quantity: {q} is not a count of lamps")));
            }
        };
        let positive = |v: Option<f64>| v.filter(|x| *x > 0.0);
        let cct_node = child(e, &["CCT", "FixedCCT"]).or_else(|| {
            child(e, &["ColorTemperature"]).and_then(|c| child(c, &["FixedCCT", "CCT"]))
        });
        let cct_k = cct_node
            .map(|n| number(self.name, self.line(n), "CCT", &element_text(n)))
            .transpose()?;
        let ra = match child(e, &["ColorRendering"]) {
            Some(c) => match child(c, &["CIE_CRI"]) {
                Some(cri) => self.number(cri, &["Ra"])?,
                None => self.number(c, &["Ra"])?,
            },
            None => None,
        };
        let intensity = self.intensity(e, gonio_type)?;
        Ok(Emitter {
            description: child(e, &["Description"])
                .map(element_text)
                .unwrap_or_default(),
            quantity,
            rated_lumens: positive(self.number(e, &["RatedLumens"])?),
            input_watts: positive(self.number(e, &["InputWattage", "InputWatts"])?),
            cct_k: positive(cct_k),
            ra: positive(ra),
            intensity,
            spectrum: child(e, &["SpectralDistribution"])
                .map(|s| self.spectrum(s))
                .transpose()?,
            openings: self.openings(e)?,
        })
    }

    /// The intensity table: the `IntData h= v=` or `IntensityData horz= vert=` elements and
    /// the settings beside them.
    fn intensity(
        &self,
        e: Node,
        gonio_type: Option<(Node, String)>,
    ) -> Result<Option<Intensity>, ParseError> {
        let is_value =
            |n: &Node| n.is_element() && matches!(n.tag_name().name(), "IntData" | "IntensityData");
        let Some(table) = e.descendants().find(|n| n.children().any(|c| is_value(&c))) else {
            return Ok(None);
        };
        if let Some(m) = child(table, &["Metric"]) {
            let metric = element_text(m);
            if !metric.eq_ignore_ascii_case("luminous") {
                return Err(self.error(
                    m,
                    format!("Metric {metric:?}: only luminous intensity (Metric Luminous) is read"),
                ));
            }
        }
        let mut points = Vec::new();
        for n in table.children().filter(is_value) {
            let tag = n.tag_name().name();
            let (h_name, v_name) = if tag == "IntData" {
                ("h", "v")
            } else {
                ("horz", "vert")
            };
            let attr = |name: &str| {
                n.attribute(name)
                    .ok_or_else(|| self.error(n, format!("{tag}: the attribute {name} is missing")))
                    .and_then(|t| number(self.name, self.line(n), name, t))
            };
            let h = attr(h_name)?;
            let v = attr(v_name)?;
            let value = number(
                self.name,
                self.line(n),
                n.tag_name().name(),
                &element_text(n),
            )?;
            points.push((h, v, value, self.line(n)));
        }
        let element = table
            .children()
            .find(is_value)
            .map(|n| n.tag_name().name())
            .unwrap_or("IntData");
        let (horizontal, vertical, values) = grid_from_points(self.name, element, &points)?;
        let type_node = child(table, &["PhotometryType", "Type"])
            .map(|t| (t, element_text(t)))
            .or(gonio_type);
        let photometry_type = match &type_node {
            None => 'C',
            Some((n, t)) => photometry_letter(t).ok_or_else(|| {
                self.error(
                    *n,
                    format!("photometry type {t:?} (expected C, B or A: Type C, CIE _ C, IES_C …)"),
                )
            })?,
        };
        let absolute = match child(table, &["AbsolutePhotometry"]) {
            None => None,
            Some(n) => Some(boolean(&element_text(n)).ok_or_else(|| {
                self.error(
                    n,
                    format!(
                        "AbsolutePhotometry: expected true or false, found {:?}",
                        element_text(n)
                    ),
                )
            })?),
        };
        let multiplier = self.number(table, &["Multiplier"])?.unwrap_or(1.0);
        if multiplier.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            let n = child(table, &["Multiplier"]).expect("just read");
            return Err(self.error(n, format!("Multiplier: {multiplier} must be above 0")));
        }
        Ok(Some(Intensity {
            photometry_type,
            symmetry: child(table, &["SymmType", "Symm"]).map(|n| (element_text(n), self.line(n))),
            absolute,
            multiplier,
            horizontal,
            vertical,
            values,
            line: points[0].3,
        }))
    }

    fn spectrum(&self, s: Node) -> Result<Spectrum, ParseError> {
        let list = |names: &[&str]| -> Result<Vec<f64>, ParseError> {
            let n = child(s, names).ok_or_else(|| {
                self.error(s, format!("SpectralDistribution: no {} element", names[0]))
            })?;
            element_text(n)
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|t| !t.is_empty())
                .map(|t| number(self.name, self.line(n), names[0], t))
                .collect()
        };
        let spectrum = Spectrum {
            wavelengths_nm: list(&["Wavelengths"])?,
            values: list(&["Values"])?,
        };
        spectrum
            .validate()
            .map_err(|m| self.error(s, format!("SpectralDistribution: {m}")))?;
        Ok(spectrum)
    }

    /// The rectangles of `EmissionAreas/BottomFace/BottomArea`.
    fn openings(&self, e: Node) -> Result<Vec<Opening>, ParseError> {
        let Some(face) = child(e, &["EmissionAreas"]).and_then(|a| child(a, &["BottomFace"]))
        else {
            return Ok(Vec::new());
        };
        face.children()
            .filter(|n| n.is_element() && n.tag_name().name() == "BottomArea")
            .map(|a| {
                let size = |names: &[&str]| -> Result<f64, ParseError> {
                    let v = self.number(a, names)?.unwrap_or(0.0);
                    if v.abs() > 1e5 {
                        return Err(
                            self.error(a, format!("BottomArea {}: {v} is not a size", names[0]))
                        );
                    }
                    Ok(v)
                };
                Ok(Opening {
                    length_m: size(&["Length"])?.abs(),
                    width_m: size(&["Width"])?.abs(),
                    length_offset_m: size(&["LengthOffset"])?,
                    width_offset_m: size(&["WidthOffset"])?,
                })
            })
            .collect()
    }
}

/// The first child element of `node` with one of `names`.
fn child<'a, 'i>(node: Node<'a, 'i>, names: &[&str]) -> Option<Node<'a, 'i>> {
    node.children()
        .find(|n| n.is_element() && names.contains(&n.tag_name().name()))
}

/// The first descendant element of `node` with one of `names`.
fn descendant<'a, 'i>(node: Node<'a, 'i>, names: &[&str]) -> Option<Node<'a, 'i>> {
    node.descendants()
        .find(|n| n.is_element() && names.contains(&n.tag_name().name()))
}

/// The text of an element, trimmed.
fn element_text(node: Node) -> String {
    node.text().unwrap_or("").trim().to_string()
}

/// The letter of a photometry type as the dialects write it ("C", "Type C", "CIE _ C",
/// "IES_C", "TypeB").
pub(super) fn photometry_letter(text: &str) -> Option<char> {
    let letters: String = text
        .chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .collect::<String>()
        .to_ascii_uppercase();
    let stripped = letters
        .trim_start_matches("CIE")
        .trim_start_matches("IES")
        .trim_start_matches("TYPE");
    match stripped {
        "C" => Some('C'),
        "B" => Some('B'),
        "A" => Some('A'),
        _ => None,
    }
}

/// `true`/`false` (any case), `1`/`0`.
pub(super) fn boolean(text: &str) -> Option<bool> {
    match text.trim().to_ascii_lowercase().as_str() {
        "true" | "1" | "yes" => Some(true),
        "false" | "0" | "no" => Some(false),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn photometry_types_are_read_in_every_spelling() {
        for (t, l) in [
            ("C", 'C'),
            ("Type C", 'C'),
            ("CIE _ C", 'C'),
            ("IES_C", 'C'),
            ("TypeB", 'B'),
            ("A", 'A'),
        ] {
            assert_eq!(photometry_letter(t), Some(l), "{t}");
        }
        assert_eq!(photometry_letter("D"), None);
    }

    #[test]
    fn errors_name_the_element_and_line() {
        let text = "<IESTM33-22>\n<Emitter>\n<LuminousData>\n<IntensityData horz=\"0\" vert=\"0\">x</IntensityData>\n</LuminousData>\n</Emitter>\n</IESTM33-22>";
        let e = read("f.xml", text, &mut Vec::new()).unwrap_err();
        assert_eq!(e.line, 4);
        assert!(e.message.contains("IntensityData"), "{e}");
        let e = read("f.xml", "<Foo/>", &mut Vec::new()).unwrap_err();
        assert!(e.message.contains("<Foo>"), "{e}");
        let e = read(
            "f.xml",
            "<IESTM33-22>\n<Header>\n</IESTM33-22>",
            &mut Vec::new(),
        )
        .unwrap_err();
        assert_eq!(e.line, 3, "{e}");
    }
}
