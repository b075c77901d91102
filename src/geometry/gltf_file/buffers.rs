//! The bytes behind a glTF document: its buffers (the GLB's binary chunk, data URIs and
//! files beside it), checked accessors, placed primitives and decoded images.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use base64::Engine as _;
use glam::{DMat3, DMat4, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::GltfPrimitive;

/// Reads a file a glTF names by a relative URI (percent-escapes decoded), bounded as
/// every model input is.
pub(super) fn read_beside(dir: &Path, uri: &str) -> Result<Vec<u8>, String> {
    let path = percent_decode(uri);
    if path.contains("://") || Path::new(&path).is_absolute() {
        return Err(format!(
            "{uri:?}: only files beside the model (relative URIs) and data URIs are read"
        ));
    }
    let file = dir.join(&path);
    crate::io::read_limited(&file, crate::io::MAX_MODEL_BYTES)
        .map_err(|e| format!("{}: {e}", file.display()))
}

fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The bytes a URI names: a base64 data URI decoded, or the file beside the model.
pub(super) fn uri_bytes(
    uri: &str,
    read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
) -> Result<Vec<u8>, String> {
    match uri.strip_prefix("data:") {
        Some(rest) => {
            let (_, payload) = rest
                .split_once(";base64,")
                .ok_or_else(|| "a data URI that is not base64".to_string())?;
            base64::engine::general_purpose::STANDARD
                .decode(payload.trim())
                .map_err(|e| format!("a data URI's base64: {e}"))
        }
        None => read_uri(uri),
    }
}

/// Every buffer's bytes, each at least as long as the document says.
pub(super) fn load(
    gltf: &gltf::Gltf,
    read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
) -> Result<Vec<Vec<u8>>, String> {
    let mut total = 0u64;
    let mut out = Vec::new();
    for b in gltf.document.buffers() {
        let at = format!("buffers[{}]", b.index());
        let bytes = match b.source() {
            gltf::buffer::Source::Bin => gltf
                .blob
                .clone()
                .ok_or_else(|| format!("{at}: the GLB has no binary chunk"))?,
            gltf::buffer::Source::Uri(uri) => {
                uri_bytes(uri, read_uri).map_err(|e| format!("{at}: {e}"))?
            }
        };
        if bytes.len() < b.length() {
            return Err(format!(
                "{at}: {} bytes, shorter than its byteLength {}",
                bytes.len(),
                b.length()
            ));
        }
        total += bytes.len() as u64;
        if total > crate::io::MAX_MODEL_BYTES {
            return Err(format!(
                "its buffers hold more than {}",
                crate::io::limits::bytes(crate::io::MAX_MODEL_BYTES)
            ));
        }
        out.push(bytes);
    }
    Ok(out)
}

/// Checks that `a` can be read: the element type is one of `types` × `dims`, it has a
/// buffer view (sparse accessors are refused), and every element lies in its view and
/// buffer. Returns its count.
fn check_accessor(
    a: &gltf::Accessor,
    data: &[Vec<u8>],
    types: &[DataType],
    dims: Dimensions,
    what: &str,
) -> Result<usize, String> {
    let at = format!("{what} (accessors[{}])", a.index());
    if a.dimensions() != dims || !types.contains(&a.data_type()) {
        return Err(format!(
            "{at}: {:?} {:?} is not a type glTF allows here",
            a.data_type(),
            a.dimensions()
        ));
    }
    if a.sparse().is_some() {
        return Err(format!("{at}: sparse accessors are not read"));
    }
    let view = a
        .view()
        .ok_or_else(|| format!("{at}: no bufferView (an all-zero accessor)"))?;
    let count = a.count();
    if count == 0 {
        return Err(format!("{at}: count 0"));
    }
    let size = a.size();
    let stride = view.stride().unwrap_or(size);
    let buffer = data
        .get(view.buffer().index())
        .ok_or_else(|| format!("{at}: its buffer is missing"))?;
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer.len()) || stride < size {
        return Err(format!(
            "bufferViews[{}] lies outside its buffer or strides less than an element",
            view.index()
        ));
    }
    let last = (count - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(a.offset()))
        .and_then(|n| n.checked_add(size));
    if last.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{at}: {count} elements run past the end of bufferViews[{}]",
            view.index()
        ));
    }
    Ok(count)
}

/// One primitive placed by a node's world matrix `world` (file frame): positions,
/// normals, texture coordinates and triangles, every index checked.
pub(super) fn primitive(
    p: &gltf::Primitive,
    data: &[Vec<u8>],
    world: DMat4,
    warnings: &mut Vec<String>,
) -> Result<GltfPrimitive, String> {
    let mode = p.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        warnings.push(format!(
            "{mode:?} primitives carry no surface and were skipped"
        ));
        return Ok(GltfPrimitive::default());
    }
    let positions = p
        .get(&gltf::Semantic::Positions)
        .ok_or("no POSITION attribute")?;
    let vertex_count = check_accessor(
        &positions,
        data,
        &[DataType::F32],
        Dimensions::Vec3,
        "POSITION",
    )?;
    let reader = p.reader(|b| data.get(b.index()).map(Vec::as_slice));
    let matrix = world;
    let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
    let mut out = GltfPrimitive {
        material: p.material().index(),
        ..Default::default()
    };
    out.positions = reader
        .read_positions()
        .ok_or("POSITION cannot be read")?
        .map(|v| matrix.transform_point3(DVec3::from_array(v.map(f64::from))))
        .collect();
    if out.positions.iter().any(|v| !v.is_finite()) {
        return Err("a vertex position is not a finite number".into());
    }
    if let Some(n) = p.get(&gltf::Semantic::Normals) {
        if check_accessor(&n, data, &[DataType::F32], Dimensions::Vec3, "NORMAL")? == vertex_count {
            out.normals = reader.read_normals().map(|it| {
                it.map(|v| {
                    (normal_matrix * DVec3::from_array(v.map(f64::from))).normalize_or_zero()
                })
                .collect()
            });
        }
    }
    if let Some(t) = p.get(&gltf::Semantic::TexCoords(0)) {
        let types = [DataType::F32, DataType::U8, DataType::U16];
        if check_accessor(&t, data, &types, Dimensions::Vec2, "TEXCOORD_0")? == vertex_count {
            out.uvs = reader.read_tex_coords(0).map(|it| it.into_f32().collect());
        }
    }
    let indices: Vec<u32> = match p.indices() {
        Some(a) => {
            let types = [DataType::U8, DataType::U16, DataType::U32];
            check_accessor(&a, data, &types, Dimensions::Scalar, "indices")?;
            reader
                .read_indices()
                .ok_or("indices cannot be read")?
                .into_u32()
                .collect()
        }
        None => (0..vertex_count as u32).collect(),
    };
    if let Some(i) = indices.iter().find(|&&i| i as usize >= vertex_count) {
        return Err(format!(
            "index {i} is out of range for its {vertex_count} vertices"
        ));
    }
    out.triangles = triangles(mode, &indices);
    // A mirroring transform turns the front faces to the back: turn them round.
    if DMat3::from_mat4(world).determinant() < 0.0 {
        for t in &mut out.triangles {
            t.swap(1, 2);
        }
    }
    Ok(out)
}

/// The triangles of a list, strip or fan.
fn triangles(mode: Mode, i: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (2..i.len())
            .map(|k| {
                if k % 2 == 0 {
                    [i[k - 2], i[k - 1], i[k]]
                } else {
                    [i[k - 1], i[k - 2], i[k]]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..i.len()).map(|k| [i[0], i[k - 1], i[k]]).collect(),
        _ => i.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// Decoded images by index, each decoded once.
#[derive(Default)]
pub(super) struct ImageCache {
    decoded: HashMap<usize, Arc<image::RgbaImage>>,
}

impl ImageCache {
    /// The image of `texture`, decoded (PNG or JPEG).
    pub(super) fn get(
        &mut self,
        texture: &gltf::Texture,
        data: &[Vec<u8>],
        read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
    ) -> Result<Arc<image::RgbaImage>, String> {
        let img = texture.source();
        if let Some(done) = self.decoded.get(&img.index()) {
            return Ok(done.clone());
        }
        let at = format!("images[{}]", img.index());
        let bytes = match img.source() {
            gltf::image::Source::View { view, .. } => {
                let buffer = data
                    .get(view.buffer().index())
                    .ok_or_else(|| format!("{at}: its buffer is missing"))?;
                let end = view.offset().checked_add(view.length());
                end.and_then(|end| buffer.get(view.offset()..end))
                    .ok_or_else(|| {
                        format!(
                            "{at}: bufferViews[{}] lies outside its buffer",
                            view.index()
                        )
                    })?
                    .to_vec()
            }
            gltf::image::Source::Uri { uri, .. } => {
                uri_bytes(uri, read_uri).map_err(|e| format!("{at}: {e}"))?
            }
        };
        let decoded = image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| format!("{at}: {e}"))?
            .decode()
            .map_err(|e| format!("{at}: {e}"))?
            .to_rgba8();
        let decoded = Arc::new(decoded);
        self.decoded.insert(img.index(), decoded.clone());
        Ok(decoded)
    }
}
