//! IES LM-63 reader (1986/1991/1995/2002/2019, Type C) and writer (LM-63-2002).
//!
//! An IES file is converted into the EULUMDAT data model so that both formats share one
//! distribution, one writer pair and one set of checks.

use super::error::ParseError;
use super::eulumdat::{Dimensions, Eulumdat, LampSet, Parsed};
use super::grid::angle_eq;
use super::symmetry::Symmetry;
use super::text::{
    check_increasing, decode_text, exact, show, show_rounded, NumberStream, SourceText, Token,
};
use super::type_b;

/// Largest luminaire or opening size accepted, metres (100 km: anything larger is a
/// broken number, and would overflow when converted).
pub const MAX_SIZE_M: f64 = 1e5;

/// Metres per unit of an IES `units type` (1 feet, 2 metres).
fn metres_per_unit(units: u8) -> f64 {
    if units == 1 {
        0.3048
    } else {
        1.0
    }
}

/// Which edition of LM-63 a file declares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IesVersion {
    /// No header line (LM-63-1986).
    Lm63_1986,
    /// `IESNA91`.
    Lm63_1991,
    /// `IESNA:LM-63-1995`.
    Lm63_1995,
    /// `IESNA:LM-63-2002`.
    Lm63_2002,
    /// `IES:LM-63-2019`.
    Lm63_2019,
}

/// Tilt data of the lamp (how output changes when the luminaire is tilted).
#[derive(Debug, Clone, PartialEq)]
pub enum Tilt {
    /// `TILT=NONE`.
    None,
    /// `TILT=INCLUDE`: lamp-to-luminaire geometry, angles and multiplying factors.
    Include {
        /// 1 vertical base-up/down, 2 horizontal along 0°, 3 horizontal along 90°.
        geometry: u8,
        /// Tilt angles, degrees.
        angles: Vec<f64>,
        /// Multiplying factors, one per angle.
        factors: Vec<f64>,
    },
    /// `TILT=<file>`: a separate tilt file (not read).
    File(String),
}

/// The shape of the luminous opening, decoded from the signs of width, length and height
/// (LM-63-2002 §5.11; a zero length with a negative width is the LM-63-1995 round form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum OpeningShape {
    /// All zero.
    Point,
    /// Width and length positive, no height.
    Rectangular,
    /// A box with luminous sides.
    RectangularWithSides,
    /// Width = length negative, no height.
    Circular,
    /// Width ≠ length, both negative, no height.
    Ellipse,
    /// Width and length negative, positive height.
    VerticalCylinder,
    /// All three negative.
    Sphere,
    /// Width negative, length positive, height negative: a cylinder along the length.
    HorizontalCylinderAlongLength,
    /// Width positive, length negative, height negative: a cylinder along the width.
    HorizontalCylinderAlongWidth,
    /// A sign pattern outside the standard.
    Other,
}

/// The luminous opening: its shape and sizes in metres.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LuminousOpening {
    /// The shape.
    pub shape: OpeningShape,
    /// Width (or diameter), m.
    pub width_m: f64,
    /// Length, m.
    pub length_m: f64,
    /// Height, m.
    pub height_m: f64,
}

/// An IES file as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct IesFile {
    /// Declared edition.
    pub version: IesVersion,
    /// Keyword lines (`[KEY] value`), `[MORE]` folded into the preceding one.
    pub keywords: Vec<(String, String)>,
    /// Tilt data.
    pub tilt: Tilt,
    /// Number of lamps.
    pub lamp_count: f64,
    /// Lumens per lamp; −1 for absolute photometry.
    pub lumens_per_lamp: f64,
    /// Candela multiplier.
    pub multiplier: f64,
    /// 1 Type C, 2 Type B, 3 Type A.
    pub photometric_type: u8,
    /// 1 feet, 2 metres.
    pub units: u8,
    /// Width, length, height of the opening in the file's units (signs encode the shape).
    pub size: [f64; 3],
    /// Ballast factor.
    pub ballast_factor: f64,
    /// Ballast-lamp photometric factor (LM-63-1995 and older) or "future use" (later).
    pub ballast_lamp_factor: f64,
    /// Input watts.
    pub input_watts: f64,
    /// Vertical (γ) angles, degrees.
    pub vertical: Vec<f64>,
    /// Horizontal (C) angles, degrees.
    pub horizontal: Vec<f64>,
    /// Candela values as stored, one row per horizontal angle.
    pub candela: Vec<Vec<f64>>,
}

impl IesFile {
    /// The value of keyword `key` (without brackets), if present.
    pub fn keyword(&self, key: &str) -> Option<&str> {
        self.keywords
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(key))
            .map(|(_, v)| v.as_str())
    }

    /// Factor from stored values to candela: multiplier × ballast factor (× the
    /// ballast-lamp photometric factor for editions that define it).
    pub fn candela_scale(&self) -> f64 {
        let old = matches!(
            self.version,
            IesVersion::Lm63_1986 | IesVersion::Lm63_1991 | IesVersion::Lm63_1995
        );
        self.multiplier * self.ballast_factor * if old { self.ballast_lamp_factor } else { 1.0 }
    }

    /// Metres per file unit.
    pub fn metres_per_unit(&self) -> f64 {
        metres_per_unit(self.units)
    }

    /// The luminous opening in metres.
    pub fn opening(&self) -> LuminousOpening {
        let k = self.metres_per_unit();
        let [w, l, h] = self.size;
        let sign = |v: f64| {
            if v > 0.0 {
                1
            } else if v < 0.0 {
                -1
            } else {
                0
            }
        };
        // LM-63-2002 sign patterns, plus the LM-63-1995 habit of a negative width (the
        // diameter) with a zero length for round shapes.
        let shape = match (sign(w), sign(l), sign(h)) {
            (0, 0, 0) => OpeningShape::Point,
            (-1, 0, 0) => OpeningShape::Circular,
            (-1, 0, 1) => OpeningShape::VerticalCylinder,
            (-1, 0, -1) => OpeningShape::Sphere,
            (0, 1, -1) => OpeningShape::HorizontalCylinderAlongLength,
            (1, 0, -1) => OpeningShape::HorizontalCylinderAlongWidth,
            (1, 1, 0) => OpeningShape::Rectangular,
            (1, 1, 1) => OpeningShape::RectangularWithSides,
            (-1, -1, 0) if w == l => OpeningShape::Circular,
            (-1, -1, 0) => OpeningShape::Ellipse,
            (-1, -1, 1) => OpeningShape::VerticalCylinder,
            (-1, -1, -1) => OpeningShape::Sphere,
            (-1, 1, -1) => OpeningShape::HorizontalCylinderAlongLength,
            (1, -1, -1) => OpeningShape::HorizontalCylinderAlongWidth,
            _ => OpeningShape::Other,
        };
        LuminousOpening {
            shape,
            width_m: w.abs() * k,
            length_m: l.abs() * k,
            height_m: h.abs() * k,
        }
    }

    /// Reads IES bytes; `name` is used in messages.
    pub fn parse(name: &str, bytes: &[u8]) -> Result<Parsed<IesFile>, ParseError> {
        let (text, decode_warnings) = decode_text(bytes);
        let src = SourceText::new(name, &text, decode_warnings);
        let mut warnings = src.warnings.clone();
        let (version, first_keyword_line) = edition(&src, &mut warnings);
        let (keywords, tilt_spec, tilt_line) = read_keywords(&src, first_keyword_line)?;
        let mut nums = NumberStream::new(&src, tilt_line + 1, &[',']);
        let tilt = read_tilt(&src, &mut nums, &tilt_spec, tilt_line, &mut warnings)?;
        let header = read_header(&src, &mut nums, version)?;
        let table = read_table(&src, &mut nums, &header)?;
        check_after_table(&src, &mut nums, &header, &mut warnings)?;
        if nums.saw_comma {
            warnings.push("decimal commas read as decimal points".to_string());
        }
        let file = IesFile {
            version,
            keywords,
            tilt,
            lamp_count: header.lamp_count.value,
            lumens_per_lamp: header.lumens.value,
            multiplier: header.multiplier.value,
            photometric_type: header.photometric_type,
            units: header.units,
            size: header.size.map(|t| t.value),
            ballast_factor: header.ballast.value,
            ballast_lamp_factor: header.blpf.value,
            input_watts: header.input_watts,
            vertical: table.vertical.iter().map(|t| t.value).collect(),
            horizontal: table.horizontal.iter().map(|t| t.value).collect(),
            candela: table.candela,
        };
        check_closing_plane(&file, &table.horizontal, &mut warnings);
        check_angle_ranges(
            &src,
            &file,
            &table.vertical,
            &table.horizontal,
            &mut warnings,
        )?;
        Ok(Parsed {
            data: file,
            warnings,
        })
    }

    /// Converts to the EULUMDAT data model (intensities in cd/klm). For absolute
    /// photometry (lumens = −1) the lamp flux becomes the integrated luminaire flux and the
    /// lamp count is negative, as EULUMDAT marks absolute photometry.
    pub fn to_eulumdat(&self, file_name: &str) -> Eulumdat {
        if self.photometric_type != 1 {
            let c_gamma = type_b::to_c_gamma(
                self.photometric_type,
                &self.vertical,
                &self.horizontal,
                &self.candela,
            );
            let as_c = IesFile {
                photometric_type: 1,
                vertical: c_gamma.gamma,
                horizontal: c_gamma.c,
                candela: c_gamma.candela,
                ..self.clone()
            };
            return as_c.to_eulumdat(file_name);
        }
        let stored_symmetry =
            horizontal_symmetry(&self.horizontal).expect("validated when parsing");
        let full = full_circle(&self.horizontal, stored_symmetry);
        // Irregular half-circles that do not split as EULUMDAT needs are stored in full.
        let symmetry = if symmetry_fits(stored_symmetry, &full) {
            stored_symmetry
        } else {
            Symmetry::None
        };
        let scale = self.candela_scale();
        // Absolute candela for any full-circle angle, through the IES storage symmetry.
        let plane_at = |c: f64| -> Vec<f64> {
            let target = match stored_symmetry {
                Symmetry::Rotational => 0.0,
                Symmetry::C90C270 => {
                    if (90.0..=270.0).contains(&c) {
                        c
                    } else {
                        (180.0 - c).rem_euclid(360.0)
                    }
                }
                s => s.fold(c),
            };
            let k = self
                .horizontal
                .iter()
                .position(|&h| angle_eq(h, target))
                .expect("full circle built from the stored angles");
            self.candela[k].iter().map(|v| v * scale).collect()
        };
        let stored = symmetry.stored_plane_indices(full.len());
        let absolute: Vec<Vec<f64>> = stored.iter().map(|&i| plane_at(full[i])).collect();
        let absolute_photometry = self.lumens_per_lamp < 0.0;
        let lamp_flux = if absolute_photometry {
            let planes: Vec<(f64, Vec<f64>)> = full.iter().map(|&c| (c, plane_at(c))).collect();
            super::flux::integrate_flux(&planes, &self.vertical).0
        } else {
            self.lamp_count * self.lumens_per_lamp
        };
        let to_cdklm = if lamp_flux > 0.0 {
            1000.0 / lamp_flux
        } else {
            0.0
        };
        let intensities: Vec<Vec<f64>> = absolute
            .iter()
            .map(|r| r.iter().map(|v| v * to_cdklm).collect())
            .collect();
        let mm = self.metres_per_unit() * 1000.0;
        let [w, l, h] = self.size.map(|v| v.abs() * mm);
        let round = self.size[0] < 0.0;
        let kw = |k: &str| self.keyword(k).unwrap_or("").replace('\n', " ");
        let count = self.lamp_count.round() as i32;
        let mut ldt = Eulumdat {
            company: kw("MANUFAC"),
            ityp: if symmetry == Symmetry::Rotational {
                1
            } else {
                3
            },
            symmetry,
            dc: uniform_step(&full),
            dg: uniform_step(&self.vertical),
            report_number: kw("TEST"),
            luminaire_name: kw("LUMINAIRE"),
            luminaire_number: kw("LUMCAT"),
            file_name: file_name.to_string(),
            date_user: if kw("DATE").is_empty() {
                kw("ISSUEDATE")
            } else {
                kw("DATE")
            },
            dimensions: Dimensions {
                length: if round { w } else { l },
                width: if round { 0.0 } else { w },
                height: h,
                area_length: if round { w } else { l },
                area_width: if round { 0.0 } else { w },
                area_heights: [0.0; 4],
            },
            dff_percent: 0.0,
            lorl_percent: 100.0,
            conversion_factor: 1.0,
            tilt_deg: 0.0,
            lamp_sets: vec![LampSet {
                count: if absolute_photometry {
                    -count.max(1)
                } else {
                    count
                },
                lamp_type: {
                    let l = kw("LAMP");
                    if l.is_empty() {
                        kw("LAMPCAT")
                    } else {
                        l
                    }
                },
                flux_lm: lamp_flux,
                color: String::new(),
                cri: String::new(),
                watts: self.input_watts,
            }],
            direct_ratios: [0.0; 10],
            c_angles: full,
            gamma_angles: self.vertical.clone(),
            intensities,
        };
        let planes = ldt.expanded();
        let (flux, down) = super::flux::integrate_flux(&planes, &ldt.gamma_angles);
        if flux > 0.0 {
            ldt.lorl_percent = flux / 10.0;
            ldt.dff_percent = down / flux * 100.0;
        }
        ldt
    }
}

/// Writes `ldt` as an IES LM-63-2002 file (Type C, metres, TILT=NONE); `source` names
/// where the data came from ("EULUMDAT", "IES Type B", …) in an `[OTHER]` line.
pub fn write_ies(ldt: &Eulumdat, source: &str) -> String {
    let lamp_flux = ldt.lamp_flux_lm();
    let absolute = ldt.is_absolute();
    let lamps: i32 = ldt
        .lamp_sets
        .iter()
        .map(|s| s.count.abs())
        .sum::<i32>()
        .max(1);
    let (horizontal, candela) = lm63_candela(ldt);
    let mut out = String::from("IESNA:LM-63-2002\r\n");
    let mut kw = |k: &str, v: &str| {
        if !v.trim().is_empty() {
            out.push_str(&format!("[{k}] {}\r\n", v.trim()));
        }
    };
    kw("TEST", &ldt.report_number);
    kw("MANUFAC", &ldt.company);
    kw("LUMCAT", &ldt.luminaire_number);
    kw("LUMINAIRE", &ldt.luminaire_name);
    kw(
        "LAMP",
        &ldt.lamp_sets
            .first()
            .map(|s| s.lamp_type.clone())
            .unwrap_or_default(),
    );
    kw("DATE", &ldt.date_user);
    kw("OTHER", &format!("written by goniolight from {source}"));
    out.push_str("TILT=NONE\r\n");
    let d = &ldt.dimensions;
    let (w, l) = if d.width == 0.0 && d.length > 0.0 {
        (-d.length / 1000.0, -d.length / 1000.0)
    } else {
        (d.width / 1000.0, d.length / 1000.0)
    };
    let lumens = if absolute {
        -1.0
    } else {
        lamp_flux / lamps as f64
    };
    let watts: f64 = ldt.lamp_sets.iter().map(|s| s.watts).sum();
    out.push_str(&format!(
        "{} {} 1 {} {} 1 2 {} {} {}\r\n1 1 {}\r\n",
        lamps,
        fmt(lumens),
        ldt.gamma_angles.len(),
        horizontal.len(),
        fmt(w),
        fmt(l),
        fmt(d.height / 1000.0),
        fmt(watts)
    ));
    write_values(&mut out, &ldt.gamma_angles);
    write_values(&mut out, &horizontal);
    for row in &candela {
        write_values(&mut out, row);
    }
    out
}

fn write_values(out: &mut String, values: &[f64]) {
    for chunk in values.chunks(10) {
        let line: Vec<String> = chunk.iter().map(|v| fmt(*v)).collect();
        out.push_str(&line.join(" "));
        out.push_str("\r\n");
    }
}

/// Exact values (the text reads back as the same number), as the LDT writer prints them.
fn fmt(v: f64) -> String {
    exact(v)
}

fn strip_prefix_ci<'a>(s: &'a str, prefix: &str) -> Option<&'a str> {
    let head = s.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| &s[prefix.len()..])
}

fn whole(src: &SourceText<'_>, t: Token, lo: i64, hi: i64) -> Result<i64, ParseError> {
    if t.value.fract() != 0.0 || t.value < lo as f64 || t.value > hi as f64 {
        return Err(src.error(
            t.line,
            format!(
                "expected a whole number between {lo} and {hi}, found {}",
                t.value
            ),
        ));
    }
    Ok(t.value as i64)
}

/// The horizontal angles an LM-63 (or TM-33) file stores for `ldt` and the candela at each
/// (cd/klm × the lamp flux), one row per horizontal angle: the table both formats write.
pub(crate) fn lm63_candela(ldt: &Eulumdat) -> (Vec<f64>, Vec<Vec<f64>>) {
    let planes = ldt.expanded();
    let horizontal = lm63_horizontal(ldt.symmetry, &planes);
    let to_cd = ldt.lamp_flux_lm() / 1000.0;
    let candela = horizontal
        .iter()
        .map(|&c| {
            let p = planes
                .iter()
                .find(|p| angle_eq(p.0, c))
                .expect("angle taken from the planes");
            p.1.iter().map(|v| v * to_cd).collect()
        })
        .collect();
    (horizontal, candela)
}

/// The horizontal angles an LM-63 (or TM-33) file stores for `planes` (the full circle of
/// a file with `symmetry`): the symmetry's range, or every plane and 360° where irregular C
/// lists do not span that range.
pub(crate) fn lm63_horizontal(symmetry: Symmetry, planes: &[(f64, Vec<f64>)]) -> Vec<f64> {
    let horizontal: Vec<f64> = match symmetry {
        Symmetry::Rotational => vec![0.0],
        Symmetry::C0C180 => planes.iter().map(|p| p.0).filter(|&c| c <= 180.0).collect(),
        Symmetry::Quadrant => planes.iter().map(|p| p.0).filter(|&c| c <= 90.0).collect(),
        Symmetry::C90C270 => planes
            .iter()
            .map(|p| p.0)
            .filter(|&c| (90.0..=270.0).contains(&c))
            .collect(),
        Symmetry::None => planes.iter().map(|p| p.0).chain([360.0]).collect(),
    };
    if horizontal_symmetry(&horizontal).is_ok() {
        horizontal
    } else {
        planes.iter().map(|p| p.0).chain([360.0]).collect()
    }
}

/// The symmetry implied by the horizontal angle range of a Type C file.
pub(crate) fn horizontal_symmetry(h: &[f64]) -> Result<Symmetry, String> {
    let first = h[0];
    let last = h[h.len() - 1];
    let sym = match (first, last) {
        _ if h.len() == 1 && first == 0.0 => Symmetry::Rotational,
        (f, l) if f == 0.0 && l == 90.0 => Symmetry::Quadrant,
        (f, l) if f == 0.0 && l == 180.0 => Symmetry::C0C180,
        (f, l) if f == 90.0 && l == 270.0 => Symmetry::C90C270,
        (f, l) if f == 0.0 && l > 180.0 => Symmetry::None,
        _ => {
            return Err(format!(
                "unsupported horizontal angle range {first}°–{last}° (expected 0, 0–90, 0–180, 90–270 or 0–360)"
            ))
        }
    };
    Ok(sym)
}

/// The full circle of C angles in `[0, 360)` implied by the stored horizontal angles.
fn full_circle(h: &[f64], symmetry: Symmetry) -> Vec<f64> {
    let mut all: Vec<f64> = match symmetry {
        Symmetry::Rotational => vec![0.0],
        Symmetry::None => h.to_vec(),
        Symmetry::C0C180 => h.iter().flat_map(|&c| [c, 360.0 - c]).collect(),
        Symmetry::C90C270 => h.iter().flat_map(|&c| [c, 180.0 - c]).collect(),
        Symmetry::Quadrant => h
            .iter()
            .flat_map(|&c| [c, 180.0 - c, 180.0 + c, 360.0 - c])
            .collect(),
    };
    for c in &mut all {
        *c = c.rem_euclid(360.0);
        if *c > 360.0 - 1e-9 {
            *c = 0.0;
        }
    }
    all.sort_by(f64::total_cmp);
    all.dedup_by(|a, b| angle_eq(*a, *b));
    all
}

/// Whether the full circle `full` splits into the stored planes of `symmetry` exactly.
fn symmetry_fits(symmetry: Symmetry, full: &[f64]) -> bool {
    if symmetry == Symmetry::Rotational {
        return true;
    }
    if symmetry.check_plane_count(full.len()).is_err() {
        return false;
    }
    let stored = symmetry.stored_plane_indices(full.len());
    stored
        .iter()
        .all(|&i| angle_eq(symmetry.fold(full[i]), full[i]))
        && full
            .iter()
            .all(|&c| stored.iter().any(|&i| angle_eq(full[i], symmetry.fold(c))))
}

fn uniform_step(a: &[f64]) -> f64 {
    if a.len() < 2 {
        return 0.0;
    }
    let step = a[1] - a[0];
    let uniform = a.windows(2).all(|w| ((w[1] - w[0]) - step).abs() < 1e-6);
    if uniform {
        step
    } else {
        0.0
    }
}

/// The LM-63 edition the first line names, and the (0-based) line the keywords start on;
/// a file without an edition line is LM-63-1986.
fn edition(src: &SourceText<'_>, warnings: &mut Vec<String>) -> (IesVersion, usize) {
    let first = src.lines.first().map(|l| l.trim()).unwrap_or("");
    match first.to_ascii_uppercase().as_str() {
        "IESNA:LM-63-1995" => (IesVersion::Lm63_1995, 1),
        "IESNA:LM-63-2002" => (IesVersion::Lm63_2002, 1),
        "IES:LM-63-2019" | "IESNA:LM-63-2019" => (IesVersion::Lm63_2019, 1),
        "IESNA91" => (IesVersion::Lm63_1991, 1),
        s if s.starts_with("IES") => {
            warnings.push(format!(
                "line 1: unknown edition {first:?}: read as LM-63-2002"
            ));
            (IesVersion::Lm63_2002, 1)
        }
        _ => (IesVersion::Lm63_1986, 0),
    }
}

/// Keyword lines as (keyword, value), labels as ("LABEL", text), in file order.
type Keywords = Vec<(String, String)>;

/// The keyword and label lines from `line` (0-based) up to `TILT=`: the keywords (`[MORE]`
/// continues the one before), the TILT value and the TILT line's number (1-based).
fn read_keywords(
    src: &SourceText<'_>,
    mut line: usize,
) -> Result<(Keywords, String, usize), ParseError> {
    let mut keywords: Keywords = Vec::new();
    loop {
        let Some(text) = src.lines.get(line) else {
            return Err(src.error(src.lines.len() + 1, "no TILT= line: not an IES LM-63 file"));
        };
        line += 1;
        let t = text.trim();
        if let Some(rest) = strip_prefix_ci(t, "TILT=").or_else(|| strip_prefix_ci(t, "TILT =")) {
            return Ok((keywords, rest.trim().to_string(), line));
        }
        if let Some(body) = t.strip_prefix('[') {
            let (key, value) = body.split_once(']').unwrap_or((body, ""));
            let value = value.trim().to_string();
            if key.eq_ignore_ascii_case("MORE") {
                if let Some(last) = keywords.last_mut() {
                    last.1.push('\n');
                    last.1.push_str(&value);
                    continue;
                }
            }
            keywords.push((key.trim().to_ascii_uppercase(), value));
        } else if !t.is_empty() {
            keywords.push(("LABEL".to_string(), t.to_string()));
        }
        if line > 1000 {
            return Err(src.error(line, "no TILT= line within the first 1000 lines"));
        }
    }
}

/// The tilt data `spec` (the value of `TILT=` on line `tilt_line`) announces: none, the
/// included table (read, not applied) or a file (not read).
fn read_tilt(
    src: &SourceText<'_>,
    nums: &mut NumberStream<'_, '_>,
    spec: &str,
    tilt_line: usize,
    warnings: &mut Vec<String>,
) -> Result<Tilt, ParseError> {
    match spec.to_ascii_uppercase().as_str() {
        "NONE" => Ok(Tilt::None),
        "INCLUDE" => {
            let geometry = whole(src, nums.next("lamp-to-luminaire geometry")?, 1, 3)? as u8;
            let n = whole(src, nums.next("number of tilt angles")?, 1, 3601)? as usize;
            let values = |nums: &mut NumberStream<'_, '_>, what| -> Result<Vec<f64>, ParseError> {
                Ok(nums.take(n, what)?.iter().map(|t| t.value).collect())
            };
            let angles = values(nums, "tilt angle")?;
            let factors = values(nums, "tilt multiplying factor")?;
            warnings.push(
                "TILT=INCLUDE data read; the distribution is used as measured (tilt factors not applied)"
                    .to_string(),
            );
            Ok(Tilt::Include {
                geometry,
                angles,
                factors,
            })
        }
        "" => Err(src.error(
            tilt_line,
            "TILT= has no value (NONE, INCLUDE or a file name)",
        )),
        _ => {
            warnings.push(format!(
                "line {tilt_line}: tilt file {spec:?} not read; the distribution is used as measured"
            ));
            Ok(Tilt::File(spec.to_string()))
        }
    }
}

/// The numbers between the tilt data and the angles, with their lines for messages.
struct Header {
    lamp_count: Token,
    lumens: Token,
    multiplier: Token,
    n_vert: usize,
    n_horiz: usize,
    photometric_type: u8,
    units: u8,
    size: [Token; 3],
    ballast: Token,
    blpf: Token,
    input_watts: f64,
}

/// A token that must be positive, else an error naming `what`.
fn positive(src: &SourceText<'_>, t: Token, what: &str) -> Result<(), ParseError> {
    if t.value <= 0.0 {
        return Err(src.error(
            t.line,
            format!("{what} must be positive, found {}", t.value),
        ));
    }
    Ok(())
}

/// Reads and checks the header numbers: lamps, lumens, multiplier, the angle counts, the
/// photometric and units types, the opening, the ballast factors and the input watts.
fn read_header(
    src: &SourceText<'_>,
    nums: &mut NumberStream<'_, '_>,
    version: IesVersion,
) -> Result<Header, ParseError> {
    let lamp_count = nums.next("number of lamps")?;
    let lumens = nums.next("lumens per lamp")?;
    let multiplier = nums.next("candela multiplier")?;
    let n_vert = whole(src, nums.next("number of vertical angles")?, 2, 3601)? as usize;
    let n_horiz = whole(src, nums.next("number of horizontal angles")?, 1, 3601)? as usize;
    let photometric_type = whole(src, nums.next("photometric type")?, 1, 3)? as u8;
    let units = whole(src, nums.next("units type")?, 1, 2)? as u8;
    let size = [
        nums.next("opening width")?,
        nums.next("opening length")?,
        nums.next("opening height")?,
    ];
    let ballast = nums.next("ballast factor")?;
    let blpf = nums.next("ballast-lamp photometric factor / future use")?;
    positive(src, ballast, "ballast factor")?;
    let old_edition = matches!(
        version,
        IesVersion::Lm63_1986 | IesVersion::Lm63_1991 | IesVersion::Lm63_1995
    );
    if old_edition {
        positive(src, blpf, "ballast-lamp photometric factor")?;
    }
    let input_watts = nums.next("input watts")?.value;
    if lumens.value <= 0.0 && lumens.value != -1.0 {
        return Err(src.error(
            lumens.line,
            format!(
                "lumens per lamp must be positive or -1, found {}",
                lumens.value
            ),
        ));
    }
    for (tok, what) in size
        .iter()
        .zip(["opening width", "opening length", "opening height"])
    {
        if tok.value.abs() * metres_per_unit(units) > MAX_SIZE_M {
            return Err(src.error(
                tok.line,
                format!("{what} {} is not the size of a luminaire", show(tok.value)),
            ));
        }
    }
    if lamp_count.value > 1e6 {
        return Err(src.error(
            lamp_count.line,
            format!(
                "number of lamps {} exceeds 1 000 000",
                show(lamp_count.value)
            ),
        ));
    }
    positive(src, lamp_count, "number of lamps")?;
    positive(src, multiplier, "candela multiplier")?;
    Ok(Header {
        lamp_count,
        lumens,
        multiplier,
        n_vert,
        n_horiz,
        photometric_type,
        units,
        size,
        ballast,
        blpf,
        input_watts,
    })
}

/// The angles (as tokens, for their lines) and the candela rows.
struct Table {
    vertical: Vec<Token>,
    horizontal: Vec<Token>,
    candela: Vec<Vec<f64>>,
}

/// Reads the angles (increasing, in the photometric type's range) and one candela row per
/// horizontal angle (none negative).
fn read_table(
    src: &SourceText<'_>,
    nums: &mut NumberStream<'_, '_>,
    header: &Header,
) -> Result<Table, ParseError> {
    let vertical = nums.take(header.n_vert, "vertical angle")?;
    let horizontal = nums.take(header.n_horiz, "horizontal angle")?;
    if header.photometric_type == 1 {
        check_increasing(src, &vertical, 0.0..=180.0, "vertical")?;
        check_increasing(src, &horizontal, 0.0..=360.0, "horizontal")?;
    } else {
        check_increasing(src, &vertical, -90.0..=90.0, "vertical")?;
        check_increasing(src, &horizontal, -90.0..=90.0, "horizontal")?;
    }
    let mut candela = Vec::with_capacity(header.n_horiz);
    for h in &horizontal {
        let row = nums.take(
            header.n_vert,
            &format!("candela value of horizontal angle {}", h.value),
        )?;
        if let Some(t) = row.iter().find(|t| t.value < 0.0) {
            return Err(src.error(t.line, format!("negative candela value {}", t.value)));
        }
        candela.push(row.iter().map(|t| t.value).collect());
    }
    Ok(Table {
        vertical,
        horizontal,
        candela,
    })
}

/// What follows the table: numbers may be a table the header miscounts (refused); end
/// markers (END, ^Z) and words cannot be (accepted with a note).
fn check_after_table(
    src: &SourceText<'_>,
    nums: &mut NumberStream<'_, '_>,
    header: &Header,
    warnings: &mut Vec<String>,
) -> Result<(), ParseError> {
    let Some(t) = nums.trailing() else {
        return Ok(());
    };
    if t.numbers > 0 {
        return Err(src.error(
            t.first_line,
            format!(
                "more data than {} vertical × {} horizontal angles announce: {} follow the table",
                header.n_vert,
                header.n_horiz,
                t.describe()
            ),
        ));
    }
    warnings.push(format!(
        "line {}: {} after the table ignored",
        t.first_line,
        t.describe()
    ));
    Ok(())
}

/// LM-63 closes a full circle with a C360 plane that repeats C0; where it does not, C0 is
/// used, and the reader is told.
fn check_closing_plane(file: &IesFile, horizontal: &[Token], warnings: &mut Vec<String>) {
    if let (Some(&0.0), Some(&360.0)) = (file.horizontal.first(), file.horizontal.last()) {
        let (first, last) = (&file.candela[0], &file.candela[file.candela.len() - 1]);
        let diff = first
            .iter()
            .zip(last)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        if diff > 0.0 {
            warnings.push(format!(
                "line {}: the C360 plane differs from C0 by up to {} cd: C0 is used",
                horizontal[horizontal.len() - 1].line,
                show_rounded(diff)
            ));
        }
    }
}

/// The angle ranges checked now, so that conversion cannot fail later (Type A and B are
/// converted to the C-γ frame, which the reader is told).
fn check_angle_ranges(
    src: &SourceText<'_>,
    file: &IesFile,
    vertical: &[Token],
    horizontal: &[Token],
    warnings: &mut Vec<String>,
) -> Result<(), ParseError> {
    if file.photometric_type == 1 {
        horizontal_symmetry(&file.horizontal).map_err(|m| src.error(horizontal[0].line, m))?;
    } else {
        type_b::check_ranges(&file.vertical, &file.horizontal)
            .map_err(|m| src.error(vertical[0].line, m))?;
        warnings.push(format!(
            "Type {} photometry converted to the C-γ frame (docs/src/design/photometry.md: beam axis at γ = 0)",
            if file.photometric_type == 2 { "B" } else { "A" }
        ));
    }
    Ok(())
}
