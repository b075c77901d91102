//! glTF 2.0 models (`.gltf` with the files it names, or `.glb`), read with the `gltf`
//! crate: the triangles of the default scene with every node's transform applied (a mesh
//! used by several nodes is placed once per node), the materials, and the lights
//! (`KHR_lights_punctual`, `EXT_lights_ies`). Positions stay in the file's frame (+Y up,
//! metres): the caller turns them to the world's +Z up as it does for a Y-up OBJ.
//!
//! Every count and byte is bounded and every index checked before the crate reads an
//! accessor, so a broken or hostile file is refused with its name and the element at
//! fault (`meshes[2].primitives[0]: …`), never a panic.

mod buffers;
mod lights;
mod materials;

use std::path::Path;

use glam::{DMat3, DMat4, DVec3};

pub use lights::{spot_falloff, GltfLight, LightKind, MAX_CANDELA};
pub use materials::{AlphaMode, GltfMaterial};

use super::{GeometryError, Mesh};

/// The most triangles a glTF may place, counting every instance (a 10-million-triangle
/// model with room to spare; a small file instancing a mesh a million times is refused
/// before it fills memory).
pub const MAX_TRIANGLES: usize = 50_000_000;
/// The most nodes a scene's hierarchy may place (instances included).
pub const MAX_NODE_INSTANCES: usize = 1_000_000;
/// The deepest node hierarchy followed (deeper ones are cycles or mistakes).
pub const MAX_NODE_DEPTH: usize = 64;

/// A glTF model as read.
#[derive(Debug, Clone, Default)]
pub struct GltfModel {
    /// The triangle primitives, one per node instance, in the file's frame.
    pub primitives: Vec<GltfPrimitive>,
    /// The materials, indexed by [`GltfPrimitive::material`].
    pub materials: Vec<GltfMaterial>,
    /// The lights placed by nodes.
    pub lights: Vec<GltfLight>,
    /// What was read with a simplification (lines and points skipped, a texture
    /// averaged), without the file's name.
    pub warnings: Vec<String>,
}

/// One mesh primitive placed by one node.
#[derive(Debug, Clone, Default)]
pub struct GltfPrimitive {
    /// The node's name (`node N` when it has none): what scene files and `casters` name.
    pub node: String,
    /// Positions, metres, node transform applied (file frame).
    pub positions: Vec<DVec3>,
    /// Unit normals, when the file gives them.
    pub normals: Option<Vec<DVec3>>,
    /// Texture coordinates (set 0), when the file gives them.
    pub uvs: Option<Vec<[f32; 2]>>,
    /// Triangles, counter-clockwise seen from the front (mirrored nodes turned back).
    pub triangles: Vec<[u32; 3]>,
    /// Index into [`GltfModel::materials`] (`None`: glTF's default material).
    pub material: Option<usize>,
}

/// Whether `path` names a glTF file (`.gltf` or `.glb`, any case).
pub fn is_gltf(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Reads a glTF file and the buffers and images it names (beside it).
pub fn read(path: &Path) -> Result<GltfModel, GeometryError> {
    let name = path.display().to_string();
    let bytes = crate::io::read_limited(path, crate::io::MAX_MODEL_BYTES).map_err(|source| {
        GeometryError::Io {
            file: name.clone(),
            source,
        }
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse(&name, &bytes, &|uri| buffers::read_beside(dir, uri))
}

/// Parses glTF bytes; `name` is used in messages and `read_uri` reads the files the
/// document names (relative URIs).
pub fn parse(
    name: &str,
    bytes: &[u8],
    read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
) -> Result<GltfModel, GeometryError> {
    let invalid = |message: String| GeometryError::Invalid(format!("{name}: {message}"));
    let gltf = checked_document(bytes).map_err(|e| invalid(format!("not glTF 2.0: {e}")))?;
    let data = buffers::load(&gltf, read_uri).map_err(invalid)?;
    let doc = &gltf.document;
    let mut model = GltfModel::default();
    let mut images = buffers::ImageCache::default();
    for m in doc.materials() {
        let material = materials::read(&m, &data, read_uri, &mut images, &mut model.warnings)
            .map_err(|e| invalid(format!("materials[{}]: {e}", m.index().unwrap_or(0))))?;
        model.materials.push(material);
    }
    let profiles = lights::ies_profiles(doc, &data, read_uri).map_err(invalid)?;
    let scene = doc
        .default_scene()
        .or_else(|| doc.scenes().next())
        .ok_or_else(|| invalid("the file has no scene".into()))?;
    let mut walk = Walk {
        data: &data,
        model: &mut model,
        profiles: &profiles,
        instances: 0,
        triangles: 0,
    };
    for node in scene.nodes() {
        walk.node(&node, DMat4::IDENTITY, 0).map_err(invalid)?;
    }
    if model.primitives.iter().all(|p| p.triangles.is_empty()) && model.lights.is_empty() {
        return Err(invalid(
            "its default scene places no triangles and no lights".into(),
        ));
    }
    Ok(model)
}

/// The document, parsed once and validated by the `gltf` crate after the checks its parser
/// and validator leave out (they would panic): a GLB header's length below the header's
/// own, and a primitive's POSITION naming an accessor that does not exist.
fn checked_document(bytes: &[u8]) -> Result<gltf::Gltf, String> {
    if bytes.starts_with(b"glTF") {
        let length = bytes
            .get(8..12)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if length.is_none_or(|n| n < 12) {
            return Err("the GLB header's length is shorter than the header".into());
        }
    }
    let unchecked = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    let root = unchecked.document.as_json();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (k, p) in mesh.primitives.iter().enumerate() {
            let bad = p
                .attributes
                .values()
                .find(|a| a.value() >= root.accessors.len());
            if let Some(a) = bad {
                return Err(format!(
                    "meshes[{m}].primitives[{k}]: accessor {} does not exist",
                    a.value()
                ));
            }
        }
    }
    // The crate's own validation, run on the document already parsed (not a second parse).
    use gltf::json::validation::Validate;
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        errors.push(format!("{}: {error}", path()));
    });
    if errors.is_empty() {
        Ok(unchecked)
    } else {
        Err(format!("validation: {}", errors.join("; ")))
    }
}

/// Walks the node hierarchy, placing meshes and lights.
struct Walk<'a> {
    data: &'a [Vec<u8>],
    model: &'a mut GltfModel,
    profiles: &'a [lights::IesProfile],
    instances: usize,
    triangles: usize,
}

impl Walk<'_> {
    fn node(&mut self, node: &gltf::Node, parent: DMat4, depth: usize) -> Result<(), String> {
        let at = format!("nodes[{}]", node.index());
        if depth > MAX_NODE_DEPTH {
            return Err(format!(
                "{at}: the node hierarchy is deeper than {MAX_NODE_DEPTH} (a node that is its own ancestor?)"
            ));
        }
        self.instances += 1;
        if self.instances > MAX_NODE_INSTANCES {
            return Err(format!(
                "the scene places more than {MAX_NODE_INSTANCES} nodes (instances counted)"
            ));
        }
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        if !local.is_finite() {
            return Err(format!("{at}: its transform is not finite"));
        }
        let world = parent * local;
        let label = node
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| format!("node {}", node.index()));
        if let Some(mesh) = node.mesh() {
            for p in mesh.primitives() {
                let at = format!("meshes[{}].primitives[{}]", mesh.index(), p.index());
                let placed = buffers::primitive(&p, self.data, world, &mut self.model.warnings)
                    .map_err(|e| format!("{at}: {e}"))?;
                self.triangles += placed.triangles.len();
                if self.triangles > MAX_TRIANGLES {
                    return Err(format!(
                        "the scene places more than {MAX_TRIANGLES} triangles (instances counted)"
                    ));
                }
                self.model.primitives.push(GltfPrimitive {
                    node: label.clone(),
                    ..placed
                });
            }
        }
        let frame = lights::frame(world);
        let position = world.transform_point3(DVec3::ZERO);
        for light in lights::placed(node, &label, self.profiles)? {
            let frame = frame
                .ok_or_else(|| format!("{at}: a light's node has no orientation (zero scale)"))?;
            self.model.lights.push(GltfLight {
                position,
                frame,
                ..light
            });
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }
}

impl GltfModel {
    /// All triangles as one mesh with each triangle's node (for shadow studies and
    /// silhouettes), node names standing for OBJ object names.
    pub fn mesh_with_nodes(&self) -> (Mesh, super::obj::ObjObjects) {
        let mut mesh = Mesh::default();
        let mut objects = super::obj::ObjObjects::default();
        for p in &self.primitives {
            let base = mesh.positions.len() as u32;
            let k = match objects.names.iter().position(|n| n == &p.node) {
                Some(k) => k,
                None => {
                    objects.names.push(p.node.clone());
                    objects.names.len() - 1
                }
            } as u32;
            mesh.positions.extend(&p.positions);
            for t in &p.triangles {
                mesh.triangles.push(t.map(|i| i + base));
                objects.of_triangle.push(k);
            }
        }
        (mesh, objects)
    }
}

/// The rotation part of `m` as a unit, right-handed frame (columns: the node's X, Y and
/// Z), `None` where it has no orientation.
pub(crate) fn orthonormal(m: DMat3) -> Option<DMat3> {
    let z = super::unit(m.z_axis)?;
    let x = super::unit(m.x_axis - z * m.x_axis.dot(z))?;
    Some(DMat3::from_cols(x, z.cross(x), z))
}
