//! `[[material]]` ([`super::file::MaterialEntry`]): the scene file overrides an MTL material by name, in every model that
//! has it (DIALux and Relux users set reflectances per surface the same way).
//!
//! ```toml
//! [[material]]
//! name = "opal"                   # an MTL material name in the scene's models
//! diffuse_transmittance = 0.3     # translucent: the far side emits diffusely
//! [[material]]
//! name = "wall"
//! diffuse_reflectance = [0.7, 0.65, 0.6]  # what radiosity reflects (Kd × texture mean)
//! ```
//!
//! Values are linear RGB or one number for all three, each in 0..=1, and a material's
//! reflectances plus transmittances may not exceed 1 in any channel. The keys
//! `specular_reflectance` (mirrors) and `specular_transmittance` (clear glass) are part of
//! the format and set [`Material::specular_reflectance`] and
//! [`Material::specular_transmittance`]: mirrors and clear glass, which radiosity and the
//! direct light of `calc` and `illuminance` pass light through
//! ([`crate::lighting::specular`]; the rendered image draws them by their diffuse part).

use glam::Vec3;

use super::file::{MaterialEntry, Rgb};
use super::model::Material;

/// Applies `entries` to `materials` (those of the scene's models). The error is the key
/// and the message: an unknown name, a value out of range, or reflectances plus
/// transmittances above 1.
pub fn apply(
    entries: &[MaterialEntry],
    materials: &mut [Material],
) -> Result<(), (String, String)> {
    for (i, entry) in entries.iter().enumerate() {
        let key = format!("material[{i}]");
        if let Some(first) = entries[..i].iter().position(|e| e.name == entry.name) {
            return Err((
                format!("{key}.name"),
                format!(
                    "{:?} is already overridden by material[{first}]; give each material one [[material]] table",
                    entry.name
                ),
            ));
        }
        let colour = |value: Option<Rgb>, field: &str| {
            value
                .map(|v| checked(v, &format!("{key}.{field}")))
                .transpose()
        };
        let reflectance = colour(entry.diffuse_reflectance, "diffuse_reflectance")?;
        let transmittance = colour(entry.diffuse_transmittance, "diffuse_transmittance")?;
        let mirror = colour(entry.specular_reflectance, "specular_reflectance")?;
        let glass = colour(entry.specular_transmittance, "specular_transmittance")?;
        let mut found = false;
        for m in materials.iter_mut().filter(|m| m.name == entry.name) {
            found = true;
            if let Some(r) = reflectance {
                let mean = m.texture_mean();
                if r.cmpgt(mean).any() {
                    return Err((
                        format!("{key}.diffuse_reflectance"),
                        format!(
                            "{r} is more than the diffuse texture's mean colour {mean} can \
                             reflect with Kd = 1"
                        ),
                    ));
                }
                m.diffuse = r / mean.max(Vec3::splat(1e-6));
            }
            if let Some(t) = transmittance {
                m.diffuse_transmittance = t;
            }
            if let Some(r) = mirror {
                m.specular_reflectance = r;
            }
            if let Some(t) = glass {
                m.specular_transmittance = t;
            }
            let sum = m.diffuse_reflectance()
                + m.diffuse_transmittance
                + m.specular_reflectance
                + m.specular_transmittance;
            if sum.max_element() > 1.0 + 1e-6 {
                return Err((
                    key.clone(),
                    format!(
                        "material {:?} would reflect {} and transmit {} diffusely and reflect \
                         {} and transmit {} specularly: more than it receives",
                        entry.name,
                        m.diffuse_reflectance(),
                        m.diffuse_transmittance,
                        m.specular_reflectance,
                        m.specular_transmittance
                    ),
                ));
            }
        }
        if !found {
            let mut known: Vec<&str> = materials.iter().skip(1).map(|m| m.name.as_str()).collect();
            known.sort_unstable();
            known.dedup();
            return Err((
                format!("{key}.name"),
                format!(
                    "no model has a material {:?} (their materials: {known:?})",
                    entry.name
                ),
            ));
        }
    }
    Ok(())
}

/// `value` as a colour when every channel is finite and within 0..=1.
fn checked(value: Rgb, key: &str) -> Result<Vec3, (String, String)> {
    let v = value.vec3();
    if !v.is_finite() || v.min_element() < 0.0 || v.max_element() > 1.0 {
        return Err((key.into(), format!("{v} must lie within 0..=1")));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opal() -> Vec<Material> {
        vec![
            Material::default(),
            Material {
                name: "opal".into(),
                diffuse: Vec3::splat(0.5),
                ..Material::default()
            },
        ]
    }

    fn entry(name: &str) -> MaterialEntry {
        MaterialEntry {
            name: name.into(),
            diffuse_reflectance: None,
            diffuse_transmittance: None,
            specular_reflectance: None,
            specular_transmittance: None,
        }
    }

    #[test]
    fn overrides_set_values_and_refuse_what_they_cannot() {
        let mut m = opal();
        let e = MaterialEntry {
            diffuse_transmittance: Some(Rgb::Grey(0.3)),
            diffuse_reflectance: Some(Rgb::Colour([0.6, 0.5, 0.4])),
            ..entry("opal")
        };
        apply(std::slice::from_ref(&e), &mut m).unwrap();
        assert_eq!(m[1].diffuse_transmittance, Vec3::splat(0.3));
        assert_eq!(m[1].diffuse_reflectance(), Vec3::new(0.6, 0.5, 0.4));
        assert_eq!(m[0].diffuse_transmittance, Vec3::ZERO, "others untouched");

        let too_much = MaterialEntry {
            diffuse_transmittance: Some(Rgb::Grey(0.6)),
            ..entry("opal")
        };
        let (key, message) = apply(&[too_much], &mut opal()).unwrap_err();
        assert_eq!(key, "material[0]");
        assert!(message.contains("more than it receives"), "{message}");

        let (key, message) = apply(&[entry("glas")], &mut opal()).unwrap_err();
        assert_eq!(key, "material[0].name");
        assert!(message.contains("\"opal\""), "{message}");

        let out_of_range = MaterialEntry {
            diffuse_transmittance: Some(Rgb::Grey(-0.1)),
            ..entry("opal")
        };
        let (key, _) = apply(&[out_of_range], &mut opal()).unwrap_err();
        assert_eq!(key, "material[0].diffuse_transmittance");

        // Specular keys set the material; with the diffuse part they may not exceed 1.
        let mut m = opal();
        let glass = MaterialEntry {
            diffuse_reflectance: Some(Rgb::Grey(0.0)),
            specular_reflectance: Some(Rgb::Grey(0.08)),
            specular_transmittance: Some(Rgb::Colour([0.9, 0.88, 0.85])),
            ..entry("opal")
        };
        apply(std::slice::from_ref(&glass), &mut m).unwrap();
        assert_eq!(m[1].specular_reflectance, Vec3::splat(0.08));
        assert_eq!(m[1].specular_transmittance, Vec3::new(0.9, 0.88, 0.85));
        assert!(m[1].is_specular() && !m[0].is_specular());
        let too_clear = MaterialEntry {
            specular_transmittance: Some(Rgb::Grey(0.9)),
            ..entry("opal")
        };
        let (key, message) = apply(&[too_clear], &mut opal()).unwrap_err();
        assert_eq!(key, "material[0]");
        assert!(message.contains("specularly"), "{message}");
    }
}
