//! The colour rendering index Ra a luminaire file states (EULUMDAT field 26e, one per
//! lamp set), read from the ways real files write it: a number (`90`, `RA85`, `71.5`),
//! a CIE colour rendering group (`1A`, `1B`, `2A`, `2B`, `1` … `4`, taken at the lowest
//! Ra of the group), or both (`1B/86`, `1A/>90`: the number wins). `0`, blanks and
//! numbers above 100 (a colour temperature in the wrong field) state nothing.

/// The lowest Ra of each CIE colour rendering group.
const GROUPS: [(&str, f64); 8] = [
    ("1a", 90.0),
    ("1b", 80.0),
    ("2a", 70.0),
    ("2b", 60.0),
    ("1", 80.0),
    ("2", 60.0),
    ("3", 40.0),
    ("4", 20.0),
];

/// The Ra that `text` states, if it states one.
pub fn ra_of(text: &str) -> Option<f64> {
    let cleaned: String = text
        .to_lowercase()
        .replace("ra", "")
        .chars()
        .filter(|c| !matches!(c, ' ' | '>' | '≥' | '=' | '\t'))
        .collect();
    let mut number = None;
    let mut group = None;
    for part in cleaned.split('/').filter(|p| !p.is_empty()) {
        if let Some((_, ra)) = GROUPS.iter().find(|(g, _)| *g == part) {
            group = Some(*ra);
        } else if let Ok(v) = part.replace(',', ".").parse::<f64>() {
            if v > 0.0 && v <= 100.0 {
                number = Some(v);
            }
        }
    }
    // A lone "1" … "4" is a group; a number with a group beside it is the number.
    number.filter(|v| *v > 4.0).or(group)
}

#[cfg(test)]
mod tests {
    use super::ra_of;

    #[test]
    fn the_forms_real_files_use() {
        for (text, ra) in [
            ("90", Some(90.0)),
            ("RA85", Some(85.0)),
            ("71.5", Some(71.5)),
            ("100", Some(100.0)),
            ("1A/>90", Some(90.0)),
            ("1B/86", Some(86.0)),
            ("1B", Some(80.0)),
            ("1", Some(80.0)),
            ("2b", Some(60.0)),
            ("Ra ≥ 80", Some(80.0)),
            ("0", None),
            ("", None),
            ("4000", None),
            ("good", None),
        ] {
            assert_eq!(ra_of(text), ra, "{text:?}");
        }
    }
}
