//! The JSON dialects: ATLA S001 JSON (PascalCase, `"FileType": "ATLA_S001_A"`,
//! `LuminousData.LuminousIntensity` with `h`, `v`, `IntDataSymm`) and eulumdat-rs's
//! camelCase JSON (`emitters[].intensityDistribution` with `horizontalAngles`,
//! `verticalAngles`, `intensities`). Keys are matched without regard to letter case; errors
//! name the key's path and the line where it first appears.

use serde_json::{Map, Value};

use super::xml::{boolean, photometry_letter};
use super::{grid_from_points, Dialect, Emitter, Header, Intensity, Opening, Tm33};
use crate::photometry::error::ParseError;
use crate::photometry::spectral::Spectrum;

/// One JSON document being read.
struct Reader<'a> {
    name: &'a str,
    text: &'a str,
}

/// Reads a JSON document.
pub(super) fn read(name: &str, text: &str) -> Result<Tm33, ParseError> {
    let root: Value = serde_json::from_str(text)
        .map_err(|e| ParseError::new(name, e.line(), format!("not valid JSON: {e}")))?;
    let r = Reader { name, text };
    let root = root
        .as_object()
        .ok_or_else(|| ParseError::new(name, 1, "the document is not a JSON object"))?;
    let dialect = if get(root, "emitters").is_some() && get(root, "FileType").is_none() {
        Dialect::OpticalDataJson
    } else if get(root, "Emitter").is_some()
        || get(root, "FileType")
            .and_then(Value::as_str)
            .is_some_and(|t| t.starts_with("ATLA"))
    {
        Dialect::AtlaJson
    } else {
        return Err(ParseError::new(
            name,
            1,
            "not a TM-33 or ATLA JSON document: no \"Emitter\" (ATLA S001) or \"emitters\" (eulumdat-rs) key",
        ));
    };
    let header = get(root, "Header")
        .and_then(Value::as_object)
        .map(|h| {
            let text = |keys: &[&str]| {
                keys.iter()
                    .find_map(|k| get(h, k).and_then(Value::as_str))
                    .unwrap_or("")
                    .to_string()
            };
            Header::from_lookup(text)
        })
        .unwrap_or_default();
    let mut dimensions_m = [0.0; 3];
    if let Some(d) = get(root, "Luminaire").and_then(|l| object_at(l, "Dimensions")) {
        for (k, keys) in [
            ["Length", "Diameter"],
            ["Width", "Width"],
            ["Height", "Height"],
        ]
        .iter()
        .enumerate()
        {
            if let Some(v) = r.number_any(d, keys, "Luminaire.Dimensions")? {
                if !(0.0..=1e5).contains(&v) {
                    return Err(r.error(
                        keys[0],
                        format!("Luminaire.Dimensions.{}: {v} is not a size", keys[0]),
                    ));
                }
                dimensions_m[k] = v;
            }
        }
    }
    let gonio_type = get(root, "Equipment")
        .and_then(|e| object_at(e, "Gonioradiometer").or_else(|| object_at(e, "Goniometer")))
        .and_then(|g| get(g, "Type").or_else(|| get(g, "GoniometerType")))
        .and_then(Value::as_str)
        .map(str::to_string);
    let emitters: Vec<&Value> = match get(root, "Emitter").or_else(|| get(root, "emitters")) {
        Some(Value::Array(a)) => a.iter().collect(),
        Some(v @ Value::Object(_)) => vec![v],
        _ => Vec::new(),
    };
    let emitters = emitters
        .into_iter()
        .enumerate()
        .map(|(i, e)| {
            let path = format!("Emitter[{i}]");
            let e = e
                .as_object()
                .ok_or_else(|| r.error("Emitter", format!("{path}: not an object")))?;
            r.emitter(e, &path, gonio_type.as_deref())
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Tm33 {
        dialect,
        header,
        dimensions_m,
        emitters,
    })
}

/// The value of `key` in `obj`, the key matched without regard to letter case.
fn get<'v>(obj: &'v Map<String, Value>, key: &str) -> Option<&'v Value> {
    obj.iter()
        .find(|(k, _)| k.eq_ignore_ascii_case(key))
        .map(|(_, v)| v)
}

/// The object at `key` of an object value.
fn object_at<'v>(v: &'v Value, key: &str) -> Option<&'v Map<String, Value>> {
    v.as_object()
        .and_then(|o| get(o, key))
        .and_then(Value::as_object)
}

impl Reader<'_> {
    /// An error about `key`, at the line where `"key"` first appears.
    fn error(&self, key: &str, message: impl Into<String>) -> ParseError {
        ParseError::new(self.name, self.line_of(key), message)
    }

    /// The line where `"key"` first appears (any letter case), 0 if nowhere.
    fn line_of(&self, key: &str) -> usize {
        let needle = format!("\"{}\"", key.to_ascii_lowercase());
        self.text
            .to_ascii_lowercase()
            .find(&needle)
            .map_or(0, |at| 1 + self.text[..at].matches('\n').count())
    }

    /// The number at the first of `keys` present in `obj` (a JSON number or a numeric
    /// string); `path` names `obj` in messages.
    fn number_any(
        &self,
        obj: &Map<String, Value>,
        keys: &[&str],
        path: &str,
    ) -> Result<Option<f64>, ParseError> {
        let Some((key, v)) = keys.iter().find_map(|k| get(obj, k).map(|v| (*k, v))) else {
            return Ok(None);
        };
        let n = match v {
            Value::Number(n) => n.as_f64(),
            Value::String(s) => s.trim().parse::<f64>().ok(),
            Value::Null => return Ok(None),
            _ => None,
        };
        n.filter(|x| x.is_finite())
            .map(Some)
            .ok_or_else(|| self.error(key, format!("{path}.{key}: expected a number, found {v}")))
    }

    /// The array of numbers at the first of `keys` in `obj`.
    fn numbers(
        &self,
        obj: &Map<String, Value>,
        keys: &[&str],
        path: &str,
    ) -> Result<Vec<f64>, ParseError> {
        let (key, v) = keys
            .iter()
            .find_map(|k| get(obj, k).map(|v| (*k, v)))
            .ok_or_else(|| self.error(keys[0], format!("{path}: no {} array", keys[0])))?;
        let list = v
            .as_array()
            .ok_or_else(|| self.error(key, format!("{path}.{key}: expected an array")))?;
        list.iter()
            .enumerate()
            .map(|(i, x)| {
                x.as_f64().filter(|f| f.is_finite()).ok_or_else(|| {
                    self.error(
                        key,
                        format!("{path}.{key}[{i}]: expected a number, found {x}"),
                    )
                })
            })
            .collect()
    }

    fn emitter(
        &self,
        e: &Map<String, Value>,
        path: &str,
        gonio_type: Option<&str>,
    ) -> Result<Emitter, ParseError> {
        let quantity = match self.number_any(e, &["Quantity"], path)? {
            None => 1,
            Some(q) if (1.0..=1e6).contains(&q) && q.fract() == 0.0 => q as u32,
            Some(q) => {
                return Err(self.error(
                    "Quantity",
                    format!("{path}.Quantity: {q} is not a count of lamps"),
                ))
            }
        };
        let positive = |v: Option<f64>| v.filter(|x| *x > 0.0);
        let cct = match e
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case("ColorTemperature"))
        {
            Some((_, Value::Object(c))) => self.number_any(c, &["FixedCCT", "CCT"], path)?,
            _ => self.number_any(e, &["CCT", "FixedCCT"], path)?,
        };
        let ra = match get(e, "ColorRendering").and_then(Value::as_object) {
            Some(c) => match get(c, "CIE_CRI").and_then(Value::as_object) {
                Some(cri) => self.number_any(cri, &["Ra"], path)?,
                None => self.number_any(c, &["Ra"], path)?,
            },
            None => None,
        };
        let spectrum = match get(e, "SpectralDistribution").and_then(Value::as_object) {
            Some(s) => {
                let spectrum = Spectrum {
                    wavelengths_nm: self.numbers(s, &["Wavelengths"], path)?,
                    values: self.numbers(s, &["Values"], path)?,
                };
                spectrum.validate().map_err(|m| {
                    self.error(
                        "SpectralDistribution",
                        format!("{path}.SpectralDistribution: {m}"),
                    )
                })?;
                Some(spectrum)
            }
            None => None,
        };
        Ok(Emitter {
            description: get(e, "Description")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string(),
            quantity,
            rated_lumens: positive(self.number_any(e, &["RatedLumens"], path)?),
            input_watts: positive(self.number_any(e, &["InputWattage", "InputWatts"], path)?),
            cct_k: positive(cct),
            ra: positive(ra),
            intensity: self.intensity(e, path, gonio_type)?,
            spectrum,
            openings: self.openings(e, path)?,
        })
    }

    fn intensity(
        &self,
        e: &Map<String, Value>,
        path: &str,
        gonio_type: Option<&str>,
    ) -> Result<Option<Intensity>, ParseError> {
        let (table, table_path) =
            match get(e, "LuminousData").and_then(|d| object_at(d, "LuminousIntensity")) {
                Some(t) => (t, format!("{path}.LuminousData.LuminousIntensity")),
                None => match get(e, "IntensityDistribution").and_then(Value::as_object) {
                    Some(t) => (t, format!("{path}.intensityDistribution")),
                    None => return Ok(None),
                },
            };
        if let Some(metric) = get(table, "Metric").and_then(Value::as_str) {
            if !metric.eq_ignore_ascii_case("luminous") {
                return Err(self.error(
                    "Metric",
                    format!("{table_path}.Metric {metric:?}: only luminous intensity (Metric Luminous) is read"),
                ));
            }
        }
        let horizontal = self.numbers(table, &["h", "HorizontalAngles"], &table_path)?;
        let vertical = self.numbers(table, &["v", "VerticalAngles"], &table_path)?;
        let value_keys = ["IntDataSymm", "IntData", "Intensities"];
        let flat = self.numbers(table, &value_keys, &table_path)?;
        let values_line = value_keys
            .iter()
            .find(|k| get(table, k).is_some())
            .map_or(0, |k| self.line_of(k));
        if flat.len() != horizontal.len() * vertical.len() {
            return Err(self.error(
                "v",
                format!(
                    "{table_path}: {} intensities for {} horizontal × {} vertical angles",
                    flat.len(),
                    horizontal.len(),
                    vertical.len()
                ),
            ));
        }
        // Row by row, a horizontal angle's vertical angles together.
        let points: Vec<(f64, f64, f64, usize)> = flat
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let (h, v) = (horizontal[k / vertical.len()], vertical[k % vertical.len()]);
                (h, v, x, values_line)
            })
            .collect();
        let (horizontal, vertical, values) = grid_from_points(self.name, &table_path, &points)?;
        let type_text = get(table, "PhotometryType")
            .and_then(Value::as_str)
            .or(gonio_type);
        let photometry_type = match type_text {
            None => 'C',
            Some(t) => photometry_letter(t).ok_or_else(|| {
                self.error(
                    "PhotometryType",
                    format!("{table_path}: photometry type {t:?} (expected C, B or A)"),
                )
            })?,
        };
        let absolute = match get(table, "AbsolutePhotometry") {
            None => None,
            Some(Value::Bool(b)) => Some(*b),
            Some(v) => Some(v.as_str().and_then(boolean).ok_or_else(|| {
                self.error(
                    "AbsolutePhotometry",
                    format!("{table_path}.AbsolutePhotometry: expected true or false, found {v}"),
                )
            })?),
        };
        let multiplier = self
            .number_any(table, &["Multiplier"], &table_path)?
            .unwrap_or(1.0);
        if multiplier.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(self.error(
                "Multiplier",
                format!("{table_path}.Multiplier: {multiplier} must be above 0"),
            ));
        }
        let symmetry = ["Symm", "SymmType"].iter().find_map(|k| {
            get(table, k)
                .and_then(Value::as_str)
                .map(|s| (s.to_string(), self.line_of(k)))
        });
        Ok(Some(Intensity {
            photometry_type,
            symmetry,
            absolute,
            multiplier,
            horizontal,
            vertical,
            values,
            line: values_line,
        }))
    }

    /// `EmissionAreas.BottomFace.BottomArea` (one object or an array).
    fn openings(&self, e: &Map<String, Value>, path: &str) -> Result<Vec<Opening>, ParseError> {
        let areas = match get(e, "EmissionAreas")
            .and_then(|a| object_at(a, "BottomFace"))
            .and_then(|f| get(f, "BottomArea"))
        {
            Some(Value::Array(a)) => a.iter().collect(),
            Some(v @ Value::Object(_)) => vec![v],
            _ => Vec::new(),
        };
        areas
            .into_iter()
            .map(|a| {
                let a = a.as_object().ok_or_else(|| {
                    self.error(
                        "BottomArea",
                        format!("{path}: a BottomArea is not an object"),
                    )
                })?;
                let at = |k: &str| -> Result<f64, ParseError> {
                    let v = self
                        .number_any(
                            a,
                            &[k],
                            &format!("{path}.EmissionAreas.BottomFace.BottomArea"),
                        )?
                        .unwrap_or(0.0);
                    if v.abs() > 1e5 {
                        return Err(self.error(k, format!("BottomArea.{k}: {v} is not a size")));
                    }
                    Ok(v)
                };
                Ok(Opening {
                    length_m: at("Length")?.abs(),
                    width_m: at("Width")?.abs(),
                    length_offset_m: at("LengthOffset")?,
                    width_offset_m: at("WidthOffset")?,
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_mismatch_names_the_path_and_line() {
        let text = "{\n\"FileType\": \"ATLA_S001_A\",\n\"Emitter\": [{\n\"LuminousData\": {\"LuminousIntensity\": {\n\"h\": [0],\n\"v\": [0, 90],\n\"IntDataSymm\": [1]}}}]}";
        let e = read("f.json", text).unwrap_err();
        assert!(e.message.contains("Emitter[0].LuminousData.LuminousIntensity: 1 intensities for 1 horizontal × 2 vertical"), "{e}");
        assert_eq!(e.line, 6);
    }

    #[test]
    fn syntax_errors_give_the_line() {
        let e = read("f.json", "{\n\"Emitter\": [\n}").unwrap_err();
        assert_eq!(e.line, 3, "{e}");
    }
}
