//! Writing TM-33-23 XML and ATLA S001 JSON: a document built from the EULUMDAT model (one
//! emitter, candela at the lamps' rated lumens or absolute candela), written with every
//! number exact (shortest round-trip form), so that reading it back gives the same data.

use serde_json::json;

use super::{Dialect, Emitter, Header, Intensity, Opening, Tm33};
use crate::photometry::eulumdat::Eulumdat;
use crate::photometry::ies::lm63_candela;
use crate::photometry::symmetry::Symmetry;

/// A document of one emitter holding `ldt`'s distribution, names, dimensions and lamps
/// (all lamp sets as one emitter); `dialect` is what it will be written as.
pub fn from_eulumdat(ldt: &Eulumdat, dialect: Dialect) -> Tm33 {
    let (horizontal, values) = lm63_candela(ldt);
    let lamp_flux = ldt.lamp_flux_lm();
    let absolute = ldt.is_absolute();
    let stored = crate::photometry::ies::horizontal_symmetry(&horizontal).unwrap_or(Symmetry::None);
    let intensity = Intensity {
        photometry_type: 'C',
        symmetry: Some((symmetry_name(stored, dialect).to_string(), 0)),
        absolute: Some(absolute),
        multiplier: 1.0,
        horizontal,
        vertical: ldt.gamma_angles.clone(),
        values,
        line: 0,
    };
    let d = &ldt.dimensions;
    let openings = if d.area_length > 0.0 {
        vec![Opening {
            length_m: d.area_length.abs() / 1000.0,
            width_m: d.area_width.abs() / 1000.0,
            length_offset_m: 0.0,
            width_offset_m: 0.0,
        }]
    } else {
        Vec::new()
    };
    let first = ldt.lamp_sets.first();
    let emitter = Emitter {
        description: first.map(|s| s.lamp_type.clone()).unwrap_or_default(),
        quantity: ldt
            .lamp_sets
            .iter()
            .map(|s| s.count.unsigned_abs())
            .sum::<u32>()
            .max(1),
        rated_lumens: (!absolute && lamp_flux > 0.0).then_some(lamp_flux),
        input_watts: Some(ldt.lamp_sets.iter().map(|s| s.watts).sum::<f64>()).filter(|w| *w > 0.0),
        cct_k: first.and_then(|s| cct_of(&s.color)),
        ra: ldt.colour_rendering_ra(),
        intensity: Some(intensity),
        spectrum: None,
        openings,
    };
    Tm33 {
        dialect,
        header: Header {
            manufacturer: ldt.company.clone(),
            catalog_number: ldt.luminaire_number.clone(),
            description: ldt.luminaire_name.clone(),
            laboratory: String::new(),
            report_number: ldt.report_number.clone(),
            report_date: ldt.date_user.clone(),
        },
        dimensions_m: [d.length, d.width, d.height].map(|v| v.abs() / 1000.0),
        emitters: vec![emitter],
    }
}

/// A colour temperature in a lamp colour text ("3000K", "tw/6500", "ww 2700 K"): the
/// first number of 1000–20000.
fn cct_of(text: &str) -> Option<f64> {
    text.split(|c: char| !c.is_ascii_digit() && c != '.')
        .filter_map(|t| t.parse::<f64>().ok())
        .find(|v| (1000.0..=20000.0).contains(v))
}

/// The symmetry as the dialect spells it.
fn symmetry_name(s: Symmetry, dialect: Dialect) -> &'static str {
    let xml = dialect == Dialect::Tm33Xml;
    match (s, xml) {
        (Symmetry::Rotational, true) => "Symm _ Full",
        (Symmetry::Quadrant, true) => "Symm _ Quad",
        (Symmetry::C0C180, true) => "Symm _ Bi0",
        (Symmetry::C90C270, true) => "Symm _ Bi90",
        (Symmetry::None, true) => "Symm _ None",
        (Symmetry::Rotational, false) => "Symm_Full",
        (Symmetry::Quadrant, false) => "Symm_Quad",
        (Symmetry::C0C180, false) => "Symm_Bi0",
        (Symmetry::C90C270, false) => "Symm_Bi90",
        (Symmetry::None, false) => "Symm_None",
    }
}

/// `text` escaped for XML content and attributes, without the control characters XML 1.0
/// cannot hold.
fn escape(text: &str) -> String {
    text.chars()
        .filter(|c| !c.is_control() || matches!(c, '\t' | '\n' | '\r'))
        .collect::<String>()
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Writes `doc` as TM-33-23 XML (`<IESTM33-22>`, dimensions in metres), its first emitter
/// with intensity data as the one written.
pub fn to_tm33_xml(doc: &Tm33) -> String {
    let h = &doc.header;
    let mut body = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33-22>\n  <Version>1.1</Version>\n",
    );
    body.push_str("  <Header>\n");
    put(&mut body, 4, "Manufacturer", h.manufacturer.clone());
    put(&mut body, 4, "CatalogNumber", h.catalog_number.clone());
    put(&mut body, 4, "Description", h.description.clone());
    put(&mut body, 4, "Laboratory", h.laboratory.clone());
    put(&mut body, 4, "ReportNumber", h.report_number.clone());
    put(&mut body, 4, "ReportDate", h.report_date.clone());
    put(&mut body, 4, "DocumentCreator", "goniolight".into());
    body.push_str("  </Header>\n  <Luminaire>\n    <Dimensions>\n");
    let [l, w, ht] = doc.dimensions_m;
    put(&mut body, 6, "Length", l.to_string());
    put(&mut body, 6, "Width", w.to_string());
    put(&mut body, 6, "Height", ht.to_string());
    body.push_str("    </Dimensions>\n    <NumEmitters>1</NumEmitters>\n  </Luminaire>\n");
    if let Some(e) = written_emitter(doc) {
        body.push_str("  <Emitter>\n");
        put(&mut body, 4, "Description", e.description.clone());
        put(&mut body, 4, "Quantity", e.quantity.to_string());
        put(&mut body, 4, "RatedLumens", opt(e.rated_lumens));
        put(&mut body, 4, "InputWattage", opt(e.input_watts));
        put(&mut body, 4, "CCT", opt(e.cct_k));
        if let Some(ra) = e.ra {
            body.push_str(&format!(
                "    <ColorRendering>\n      <Ra>{ra}</Ra>\n    </ColorRendering>\n"
            ));
        }
        let t = e.intensity.as_ref().expect("written emitters have data");
        body.push_str("    <LuminousData>\n");
        put(&mut body, 6, "PhotometryType", "CIE _ C".into());
        put(&mut body, 6, "Metric", "Luminous".into());
        put(
            &mut body,
            6,
            "SymmType",
            t.symmetry.as_ref().map(|s| s.0.clone()).unwrap_or_default(),
        );
        put(&mut body, 6, "Multiplier", t.multiplier.to_string());
        put(
            &mut body,
            6,
            "AbsolutePhotometry",
            t.absolute.unwrap_or(false).to_string(),
        );
        for (hz, row) in t.horizontal.iter().zip(&t.values) {
            for (v, x) in t.vertical.iter().zip(row) {
                body.push_str(&format!(
                    "      <IntensityData horz=\"{hz}\" vert=\"{v}\">{x}</IntensityData>\n"
                ));
            }
        }
        body.push_str("    </LuminousData>\n");
        if let Some(s) = &e.spectrum {
            body.push_str("    <SpectralDistribution>\n");
            put(&mut body, 6, "Wavelengths", join(&s.wavelengths_nm));
            put(&mut body, 6, "Values", join(&s.values));
            body.push_str("    </SpectralDistribution>\n");
        }
        write_openings_xml(&mut body, &e.openings);
        body.push_str("  </Emitter>\n");
    }
    body.push_str("</IESTM33-22>\n");
    body
}

/// Appends `<tag>value</tag>` at `indent` spaces, unless `value` is empty.
fn put(out: &mut String, indent: usize, tag: &str, value: String) {
    if !value.is_empty() {
        out.push_str(&format!(
            "{:indent$}<{tag}>{}</{tag}>\n",
            "",
            escape(&value)
        ));
    }
}

/// The `EmissionAreas` element of the openings, if any.
fn write_openings_xml(body: &mut String, openings: &[Opening]) {
    if openings.is_empty() {
        return;
    }
    body.push_str(&format!(
        "    <EmissionAreas>\n      <BottomFace>\n        <NumberBottom>{}</NumberBottom>\n",
        openings.len()
    ));
    for o in openings {
        body.push_str(&format!(
            "        <BottomArea>\n          <Length>{}</Length>\n          <Width>{}</Width>\n          <LengthOffset>{}</LengthOffset>\n          <WidthOffset>{}</WidthOffset>\n        </BottomArea>\n",
            o.length_m, o.width_m, o.length_offset_m, o.width_offset_m
        ));
    }
    body.push_str("      </BottomFace>\n    </EmissionAreas>\n");
}

/// Writes `doc` as ATLA S001 JSON (the specification's JSON form), its first emitter with
/// intensity data as the one written.
pub fn to_atla_json(doc: &Tm33) -> String {
    let h = &doc.header;
    let [l, w, ht] = doc.dimensions_m;
    let mut root = json!({
        "FileType": "ATLA_S001_A",
        "Version": 1.0,
        "Header": {
            "Manufacturer": h.manufacturer,
            "CatalogNumber": h.catalog_number,
            "Description": h.description,
            "Laboratory": h.laboratory,
            "ReportNumber": h.report_number,
            "ReportDate": h.report_date,
            "DocumentCreator": "goniolight",
        },
        "Luminaire": {"Dimensions": {"Length": l, "Width": w, "Height": ht}, "NumEmitter": 1},
        "Equipment": {"Gonioradiometer": {"Type": "IES_C"}},
    });
    if let Some(e) = written_emitter(doc) {
        let t = e.intensity.as_ref().expect("written emitters have data");
        let mut emitter = json!({
            "Quantity": e.quantity,
            "Description": e.description,
            "LuminousData": {"LuminousIntensity": {
                "AbsolutePhotometry": t.absolute.unwrap_or(false),
                "Symm": t.symmetry.as_ref().map(|s| s.0.clone()).unwrap_or_default(),
                "NumberMeasured": t.horizontal.len() * t.vertical.len(),
                "NumberHorz": t.horizontal.len(),
                "NumberVert": t.vertical.len(),
                "Multiplier": t.multiplier,
                "h": t.horizontal,
                "v": t.vertical,
                "IntData": t.values.concat(),
            }},
        });
        let obj = emitter.as_object_mut().expect("built as an object");
        if let Some(v) = e.rated_lumens {
            obj.insert("RatedLumens".into(), json!(v));
        }
        if let Some(v) = e.input_watts {
            obj.insert("InputWattage".into(), json!(v));
        }
        if let Some(v) = e.cct_k {
            obj.insert("ColorTemperature".into(), json!({"FixedCCT": v}));
        }
        if let Some(v) = e.ra {
            obj.insert("ColorRendering".into(), json!({"CIE_CRI": {"Ra": v}}));
        }
        if let Some(s) = &e.spectrum {
            obj.insert(
                "SpectralDistribution".into(),
                json!({"Wavelengths": s.wavelengths_nm, "Values": s.values}),
            );
        }
        if !e.openings.is_empty() {
            let areas: Vec<_> = e
                .openings
                .iter()
                .map(|o| json!({"Length": o.length_m, "Width": o.width_m, "LengthOffset": o.length_offset_m, "WidthOffset": o.width_offset_m}))
                .collect();
            obj.insert(
                "EmissionAreas".into(),
                json!({"BottomFace": {"NumberBottom": areas.len(), "BottomArea": areas}}),
            );
        }
        root["Emitter"] = json!([emitter]);
    }
    let mut text = serde_json::to_string_pretty(&root).expect("plain JSON values");
    text.push('\n');
    text
}

/// The emitter written: the first with intensity data.
fn written_emitter(doc: &Tm33) -> Option<&Emitter> {
    doc.emitters.iter().find(|e| e.intensity.is_some())
}

/// An optional number as text ("" for none).
fn opt(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

/// Numbers separated by spaces.
fn join(values: &[f64]) -> String {
    values
        .iter()
        .map(f64::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_temperatures_are_found_in_lamp_colour_texts() {
        assert_eq!(cct_of("tw/6500"), Some(6500.0));
        assert_eq!(cct_of("3000K"), Some(3000.0));
        assert_eq!(cct_of("ww"), None);
        assert_eq!(cct_of("1B 840"), None);
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(
            escape("A & B <x> \"q\"\0"),
            "A &amp; B &lt;x&gt; &quot;q&quot;"
        );
    }
}
