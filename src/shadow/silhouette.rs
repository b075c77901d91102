//! Silhouette edges of a mesh for a light, by brute force over the edge list.
//!
//! Faces are stored as planes (n, d) with unit n in a frame where the mesh is centred at
//! the origin and fits in the unit ball, so the planes are the dual points the hextree
//! indexes. A face is lit when plane · L > 0 (L in the same frame); brute force and
//! hextree evaluate exactly this expression, so they give identical edge sets.

use glam::{DVec3, Vec4};

use super::Light;
use crate::geometry::adjacency::{Adjacency, EdgeKind};
use crate::geometry::weld::{weld, Welded};
use crate::geometry::{GeometryError, Mesh};

/// A consistently wound manifold edge: `a < b`, the face traversing a→b and the one b→a.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ManifoldEdge {
    /// Smaller vertex.
    pub a: u32,
    /// Larger vertex.
    pub b: u32,
    /// Face traversing a→b.
    pub forward: u32,
    /// Face traversing b→a.
    pub backward: u32,
}

/// Silhouette edges, directed as the lit faces traverse them (an edge appears |count|
/// times under the rule of [`crate::geometry::adjacency`]), in welded vertex numbering.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Silhouette {
    /// Directed edges `[from, to]`.
    pub edges: Vec<[u32; 2]>,
}

impl Silhouette {
    /// Undirected, sorted, unique `[i, j]` (i < j).
    pub fn undirected(&self) -> Vec<[u32; 2]> {
        let mut v: Vec<[u32; 2]> = self
            .edges
            .iter()
            .map(|&[a, b]| [a.min(b), a.max(b)])
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Directed edges sorted (for comparisons between methods).
    pub fn sorted(&self) -> Vec<[u32; 2]> {
        let mut v = self.edges.clone();
        v.sort_unstable();
        v
    }
}

/// A mesh prepared for silhouette queries.
#[derive(Debug, Clone)]
pub struct SilhouetteMesh {
    /// The welded mesh and the maps to the input's numbering.
    pub welded: Welded,
    /// Its edges.
    pub adjacency: Adjacency,
    /// Face planes in the normalised frame (unit normal, offset), in f32: both methods
    /// evaluate the same f32 expression, and half the memory keeps queries in cache.
    pub planes: Vec<Vec4>,
    /// Consistently wound manifold edges (the hextree indexes these).
    pub manifold: Vec<ManifoldEdge>,
    /// Indices into `adjacency.edges` of every other edge (border, inconsistent,
    /// non-manifold), tested directly by every method.
    pub others: Vec<u32>,
    /// Per face: whether it belongs to an open surface (a connected part with an edge
    /// that is not manifold: a border, faces wound alike, or a partition), which casts a shadow from whichever side the light reaches: its faces turned
    /// from the light count as lit with their winding reversed. A closed part's unlit
    /// faces need not (the lit ones' volume already holds their shadow).
    pub two_sided: Vec<bool>,
    /// Degenerate triangles dropped.
    pub degenerate: usize,
    center: DVec3,
    scale: f64,
}

impl SilhouetteMesh {
    /// Welds vertices within `weld_tolerance` (relative to the bounding-box diagonal),
    /// drops degenerate triangles and builds planes and adjacency.
    pub fn new(mesh: &Mesh, name: &str, weld_tolerance: f64) -> Result<Self, GeometryError> {
        mesh.validate(name)?;
        let (lo, hi) = mesh.bounds().expect("validated non-empty");
        let diag = (hi - lo).length();
        let mut welded = weld(mesh, weld_tolerance * diag);
        let degenerate = welded.mesh.remove_degenerate();
        if welded.mesh.triangles.is_empty() {
            return Err(GeometryError::Invalid(format!(
                "{name}: every triangle is degenerate (zero area)"
            )));
        }
        let center = (lo + hi) * 0.5;
        let scale = (diag * 0.5).max(f64::MIN_POSITIVE);
        let m = &welded.mesh;
        let planes = (0..m.triangles.len())
            .map(|t| {
                let n = m.face_normal(t).normalize();
                let p = (m.positions[m.triangles[t][0] as usize] - center) / scale;
                n.extend(-n.dot(p)).as_vec4()
            })
            .collect();
        let adjacency = Adjacency::build(m);
        let two_sided = open_surfaces(&adjacency, m.triangles.len());
        let mut manifold = Vec::new();
        let mut others = Vec::new();
        for (i, e) in adjacency.edges.iter().enumerate() {
            if adjacency.kind(e) == EdgeKind::Manifold {
                let f = adjacency.faces(e);
                let (fw, bw) = if f[0].forward {
                    (f[0].face, f[1].face)
                } else {
                    (f[1].face, f[0].face)
                };
                let edge = ManifoldEdge {
                    a: e.a,
                    b: e.b,
                    forward: fw,
                    backward: bw,
                };
                manifold.push(edge);
            } else {
                others.push(i as u32);
            }
        }
        Ok(SilhouetteMesh {
            welded,
            adjacency,
            planes,
            manifold,
            others,
            two_sided,
            degenerate,
            center,
            scale,
        })
    }

    /// The welded mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.welded.mesh
    }

    /// The light in the normalised frame (same plane · L signs as in the world).
    pub fn light_in_frame(&self, light: &Light) -> Vec4 {
        let l = light.0;
        let xyz = (l.truncate() - l.w * self.center) / self.scale;
        // Scale to unit length: the signs are unchanged and f32 keeps its precision.
        let v = xyz.extend(l.w);
        (v / v.length()).as_vec4()
    }

    /// Whether face `f` is lit by `l` (a light in the normalised frame).
    #[inline]
    pub fn lit(&self, f: u32, l: Vec4) -> bool {
        self.planes[f as usize].dot(l) > 0.0
    }

    /// Lit flags of every face.
    pub fn lit_faces(&self, light: &Light) -> Vec<bool> {
        let l = self.light_in_frame(light);
        self.planes.iter().map(|p| p.dot(l) > 0.0).collect()
    }

    /// Appends the silhouette contribution of a manifold edge a–b (`lit_fw`: the face
    /// traversing a→b is lit). Where an open surface (`two_sided`, asked only for a
    /// silhouette edge) turns from facing the light to facing away, both faces count as lit
    /// (one reversed) and each of their volumes has a side here: the edge is given twice.
    #[inline]
    pub(crate) fn push_manifold(
        out: &mut Vec<[u32; 2]>,
        [a, b]: [u32; 2],
        lit_fw: bool,
        lit_bw: bool,
        two_sided: impl FnOnce() -> bool,
    ) {
        if lit_fw != lit_bw {
            let edge = if lit_fw { [a, b] } else { [b, a] };
            out.push(edge);
            if two_sided() {
                out.push(edge);
            }
        }
    }

    /// Appends the silhouette edges among the non-manifold-kind edges (signed counts).
    pub(crate) fn other_edges(&self, l: Vec4, out: &mut Vec<[u32; 2]>) {
        for &i in &self.others {
            let e = &self.adjacency.edges[i as usize];
            // A face counts +1 lit running a→b, −1 lit running b→a; an open surface's face
            // turned from the light counts as lit with its winding reversed.
            let count: i64 = self
                .adjacency
                .faces(e)
                .iter()
                .map(|inc| {
                    let sign = if inc.forward { 1 } else { -1 };
                    match (self.lit(inc.face, l), self.two_sided[inc.face as usize]) {
                        (true, _) => sign,
                        (false, true) => -sign,
                        (false, false) => 0,
                    }
                })
                .sum();
            let dir = if count > 0 { [e.a, e.b] } else { [e.b, e.a] };
            out.extend(std::iter::repeat_n(dir, count.unsigned_abs() as usize));
        }
    }

    /// Silhouette by testing every edge.
    pub fn brute(&self, light: &Light) -> Silhouette {
        let l = self.light_in_frame(light);
        let lit: Vec<bool> = self.planes.iter().map(|p| p.dot(l) > 0.0).collect();
        let mut edges = Vec::new();
        for e in &self.manifold {
            Self::push_manifold(
                &mut edges,
                [e.a, e.b],
                lit[e.forward as usize],
                lit[e.backward as usize],
                || self.two_sided[e.forward as usize],
            );
        }
        self.other_edges(l, &mut edges);
        Silhouette { edges }
    }

    /// The faces a light's volume starts from: the lit ones as wound, and an open
    /// surface's faces turned from the light reversed (its lit side is the back).
    pub fn cap_faces(&self, light: &Light) -> Vec<[u32; 3]> {
        let l = self.light_in_frame(light);
        self.mesh()
            .triangles
            .iter()
            .enumerate()
            .filter_map(|(f, &[a, b, c])| {
                if self.lit(f as u32, l) {
                    Some([a, b, c])
                } else if self.two_sided[f] {
                    Some([a, c, b])
                } else {
                    None
                }
            })
            .collect()
    }

    /// Undirected silhouette edges in the input's vertex numbering (the smallest input
    /// index of each welded vertex), i < j, sorted and unique.
    pub fn to_input_indices(&self, s: &Silhouette) -> Vec<[u32; 2]> {
        let rep = &self.welded.representative;
        let mut v: Vec<[u32; 2]> = s
            .edges
            .iter()
            .map(|&[a, b]| {
                let (i, j) = (rep[a as usize], rep[b as usize]);
                [i.min(j), i.max(j)]
            })
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// Per face of `face_count`: whether its connected part (faces joined by edges that two or
/// more faces share) is open: has an edge that is not manifold (a border, two faces wound
/// alike, or three or more faces: a partition inside a closed room). Only a closed,
/// consistently wound part holds its unlit faces' shadow in its lit faces' volume.
fn open_surfaces(adjacency: &Adjacency, face_count: usize) -> Vec<bool> {
    let mut parent: Vec<u32> = (0..face_count as u32).collect();
    fn root(parent: &mut [u32], mut f: u32) -> u32 {
        while parent[f as usize] != f {
            let up = parent[parent[f as usize] as usize];
            parent[f as usize] = up;
            f = up;
        }
        f
    }
    let mut border_faces = Vec::new();
    for e in &adjacency.edges {
        let faces = adjacency.faces(e);
        if adjacency.kind(e) != EdgeKind::Manifold {
            border_faces.push(faces[0].face);
        }
        for w in faces.windows(2) {
            let (a, b) = (root(&mut parent, w[0].face), root(&mut parent, w[1].face));
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut open_root = vec![false; face_count];
    for f in border_faces {
        let r = root(&mut parent, f);
        open_root[r as usize] = true;
    }
    (0..face_count as u32)
        .map(|f| open_root[root(&mut parent, f) as usize])
        .collect()
}
