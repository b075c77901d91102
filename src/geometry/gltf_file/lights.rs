//! glTF lights: `KHR_lights_punctual` (point, spot, directional) and `EXT_lights_ies`
//! (an IES LM-63 profile the file names or embeds), each placed by its node.

use std::sync::Arc;

use glam::{DMat3, DMat4, DVec3};
use serde_json::Value;

/// A light placed by a node (file frame).
#[derive(Debug, Clone)]
pub struct GltfLight {
    /// The node's name (`node N` when it has none): what a scene file replaces it by.
    pub node: String,
    /// Where it is, metres (file frame).
    pub position: DVec3,
    /// The node's orientation as a unit, right-handed frame: the light points along the
    /// third column's negative (glTF's −Z); for an IES profile the first column is C0 and
    /// the second C90.
    pub frame: DMat3,
    /// Linear RGB colour (as the file gives it; the caller normalises it).
    pub color: [f64; 3],
    /// What it is.
    pub kind: LightKind,
}

/// The kind of a glTF light, in photometric units as the extensions define them.
#[derive(Debug, Clone, PartialEq)]
pub enum LightKind {
    /// `point`: the same intensity in every direction, cd.
    Point {
        /// Intensity, cd.
        candela: f64,
    },
    /// `spot`: `candela` on its axis, falling to 0 between the inner and outer cone
    /// angles (radians from the axis) as the extension's smooth falloff.
    Spot {
        /// Intensity on the axis, cd.
        candela: f64,
        /// Where the falloff starts, radians from the axis.
        inner_cone: f64,
        /// Where the light ends, radians from the axis.
        outer_cone: f64,
    },
    /// `directional`: parallel light, lux on a surface facing it.
    Directional {
        /// Illuminance, lx.
        lux: f64,
    },
    /// `EXT_lights_ies`: a measured profile.
    Ies {
        /// The profile's name, or its URI, or `lights[N]`.
        profile: String,
        /// The IES file's bytes.
        bytes: Arc<Vec<u8>>,
        /// The node's `multiplier`.
        multiplier: f64,
    },
}

/// The largest intensity a glTF light may state, cd (a lighthouse is about 10⁷).
pub const MAX_CANDELA: f64 = 1e12;

/// An `EXT_lights_ies` profile of the document.
#[derive(Debug, Clone)]
pub(super) struct IesProfile {
    name: String,
    bytes: Arc<Vec<u8>>,
}

/// The document's `EXT_lights_ies` profiles, their bytes read.
pub(super) fn ies_profiles(
    doc: &gltf::Document,
    data: &[Vec<u8>],
    read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
) -> Result<Vec<IesProfile>, String> {
    let Some(list) = doc
        .extensions()
        .and_then(|e| e.get("EXT_lights_ies"))
        .map(|e| e.get("lights").and_then(Value::as_array))
    else {
        return Ok(Vec::new());
    };
    let list = list.ok_or("extensions.EXT_lights_ies has no lights array")?;
    list.iter()
        .enumerate()
        .map(|(k, l)| {
            let at = format!("extensions.EXT_lights_ies.lights[{k}]");
            let bytes = match (l.get("uri").and_then(Value::as_str), l.get("bufferView")) {
                (Some(uri), _) => super::buffers::uri_bytes(uri, read_uri),
                (None, Some(v)) => view_bytes(doc, data, v),
                (None, None) => Err("neither uri nor bufferView".to_string()),
            }
            .map_err(|e| format!("{at}: {e}"))?;
            let name = l
                .get("name")
                .and_then(Value::as_str)
                .or_else(|| l.get("uri").and_then(Value::as_str))
                .map_or_else(|| format!("lights[{k}]"), str::to_string);
            Ok(IesProfile {
                name,
                bytes: Arc::new(bytes),
            })
        })
        .collect()
}

fn view_bytes(doc: &gltf::Document, data: &[Vec<u8>], v: &Value) -> Result<Vec<u8>, String> {
    let view = v
        .as_u64()
        .and_then(|i| doc.views().nth(i as usize))
        .ok_or("its bufferView does not exist")?;
    let buffer = data
        .get(view.buffer().index())
        .ok_or("its buffer is missing")?;
    view.offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .map(<[u8]>::to_vec)
        .ok_or_else(|| "its bufferView lies outside its buffer".to_string())
}

/// The node's orientation ([`super::orthonormal`] of its world matrix).
pub(super) fn frame(world: DMat4) -> Option<DMat3> {
    super::orthonormal(DMat3::from_mat4(world))
}

/// The lights node `node` places (position and frame are the caller's to fill).
pub(super) fn placed(
    node: &gltf::Node,
    label: &str,
    profiles: &[IesProfile],
) -> Result<Vec<GltfLight>, String> {
    let at = format!("nodes[{}]", node.index());
    let mut out = Vec::new();
    let light = |color: [f64; 3], kind| GltfLight {
        node: label.to_string(),
        position: DVec3::ZERO,
        frame: DMat3::IDENTITY,
        color,
        kind,
    };
    // A node with both carries the KHR light as the fallback of its IES profile.
    let ies = node.extension_value("EXT_lights_ies");
    if let Some(l) = node.light().filter(|_| ies.is_none()) {
        let candela = f64::from(l.intensity());
        if !(candela.is_finite() && (0.0..=MAX_CANDELA).contains(&candela)) {
            return Err(format!(
                "{at}: KHR_lights_punctual light {}: intensity {candela} is not in 0…{MAX_CANDELA:e}",
                l.index()
            ));
        }
        let kind = match l.kind() {
            gltf::khr_lights_punctual::Kind::Point => LightKind::Point { candela },
            gltf::khr_lights_punctual::Kind::Directional => LightKind::Directional { lux: candela },
            gltf::khr_lights_punctual::Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => {
                let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
                if !(0.0 <= inner && inner < outer && outer <= std::f64::consts::FRAC_PI_2) {
                    return Err(format!(
                        "{at}: KHR_lights_punctual spot {}: cone angles {inner} and {outer} rad need 0 ≤ inner < outer ≤ π/2",
                        l.index()
                    ));
                }
                LightKind::Spot {
                    candela,
                    inner_cone: inner,
                    outer_cone: outer,
                }
            }
        };
        out.push(light(l.color().map(f64::from), kind));
    }
    if let Some(ext) = ies {
        let index = ext
            .get("light")
            .and_then(Value::as_u64)
            .ok_or_else(|| format!("{at}: EXT_lights_ies has no light index"))?;
        let profile = profiles.get(index as usize).ok_or_else(|| {
            format!(
                "{at}: EXT_lights_ies light {index} does not exist ({} profiles)",
                profiles.len()
            )
        })?;
        let multiplier = ext.get("multiplier").map_or(Some(1.0), Value::as_f64);
        let multiplier = multiplier
            .filter(|m| m.is_finite() && (0.0..=1e6).contains(m))
            .ok_or_else(|| format!("{at}: EXT_lights_ies multiplier must be a number in 0…1e6"))?;
        let color = match ext.get("color") {
            None => [1.0; 3],
            Some(c) => color3(c)
                .ok_or_else(|| format!("{at}: EXT_lights_ies color is not three numbers"))?,
        };
        out.push(light(
            color.map(|c| c.clamp(0.0, 1.0)),
            LightKind::Ies {
                profile: profile.name.clone(),
                bytes: profile.bytes.clone(),
                multiplier,
            },
        ));
    }
    Ok(out)
}

fn color3(v: &Value) -> Option<[f64; 3]> {
    let a = v.as_array()?;
    if a.len() != 3 {
        return None;
    }
    let c = [a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?];
    c.iter().all(|x| x.is_finite()).then_some(c)
}

/// The intensity of a `KHR_lights_punctual` spot at `angle` radians from its axis,
/// relative to the axis: the extension's smooth falloff,
/// `clamp((cos θ − cos outer) / (cos inner − cos outer), 0, 1)²`.
pub fn spot_falloff(angle: f64, inner_cone: f64, outer_cone: f64) -> f64 {
    let (ci, co) = (inner_cone.cos(), outer_cone.cos());
    let t = ((angle.cos() - co) / (ci - co).max(1e-3)).clamp(0.0, 1.0);
    t * t
}
