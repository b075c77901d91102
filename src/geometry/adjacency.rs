//! Edges with their faces.
//!
//! Each undirected edge lists its incident faces with the direction in which each face
//! traverses it. Kinds: **manifold** (two faces traversing it in opposite directions),
//! **border** (one face: a silhouette candidate on its own, as in Wallner §1.2),
//! **inconsistent** (two faces traversing it in the same direction: winding flips across
//! it), **non-manifold** (more than two faces).
//!
//! Rule used for every kind (documented in docs/src/design/silhouettes-and-shadow-volumes.md): for a light, an edge's signed count
//! is the number of lit faces traversing it a→b minus those traversing it b→a; the edge is
//! a silhouette edge when that count is non-zero, and the shadow volume gets |count| side
//! quads for it. For manifold edges this is "one face lit, the other not"; for border edges
//! "its face is lit"; it keeps shadow volumes closed for the other kinds as well.

use super::Mesh;

/// What kind of edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeKind {
    /// Two faces, opposite directions.
    Manifold,
    /// One face.
    Border,
    /// Two faces, the same direction.
    Inconsistent,
    /// More than two faces.
    NonManifold,
}

/// An undirected edge `a < b` and its faces (a range into [`Adjacency::incidences`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// Smaller vertex index.
    pub a: u32,
    /// Larger vertex index.
    pub b: u32,
    /// First incidence.
    pub start: u32,
    /// Number of incident faces.
    pub count: u32,
}

/// A face using an edge: the face and whether it traverses the edge a→b.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Incidence {
    /// Triangle index.
    pub face: u32,
    /// True when the face traverses a→b (with a < b).
    pub forward: bool,
}

/// Edge adjacency of a mesh.
#[derive(Debug, Clone)]
pub struct Adjacency {
    /// Unique edges sorted by (a, b).
    pub edges: Vec<Edge>,
    /// Incidences of all edges, grouped by edge.
    pub incidences: Vec<Incidence>,
}

impl Adjacency {
    /// Builds the adjacency of `mesh` (welded, without degenerate triangles).
    pub fn build(mesh: &Mesh) -> Adjacency {
        let mut half: Vec<(u32, u32, Incidence)> = Vec::with_capacity(mesh.triangles.len() * 3);
        for (f, t) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (u, v) = (t[k], t[(k + 1) % 3]);
                half.push((
                    u.min(v),
                    u.max(v),
                    Incidence {
                        face: f as u32,
                        forward: u < v,
                    },
                ));
            }
        }
        half.sort_unstable_by_key(|h| (h.0, h.1, h.2.face));
        let mut edges = Vec::new();
        let mut incidences = Vec::with_capacity(half.len());
        let mut i = 0;
        while i < half.len() {
            let (a, b) = (half[i].0, half[i].1);
            let start = incidences.len() as u32;
            while i < half.len() && half[i].0 == a && half[i].1 == b {
                incidences.push(half[i].2);
                i += 1;
            }
            edges.push(Edge {
                a,
                b,
                start,
                count: incidences.len() as u32 - start,
            });
        }
        Adjacency { edges, incidences }
    }

    /// The faces of edge `e`.
    pub fn faces(&self, e: &Edge) -> &[Incidence] {
        &self.incidences[e.start as usize..(e.start + e.count) as usize]
    }

    /// The kind of edge `e`.
    pub fn kind(&self, e: &Edge) -> EdgeKind {
        let f = self.faces(e);
        match f.len() {
            1 => EdgeKind::Border,
            2 if f[0].forward != f[1].forward => EdgeKind::Manifold,
            2 => EdgeKind::Inconsistent,
            _ => EdgeKind::NonManifold,
        }
    }

    /// How many edges of each kind: (manifold, border, inconsistent, non-manifold).
    pub fn census(&self) -> [usize; 4] {
        let mut c = [0; 4];
        for e in &self.edges {
            c[match self.kind(e) {
                EdgeKind::Manifold => 0,
                EdgeKind::Border => 1,
                EdgeKind::Inconsistent => 2,
                EdgeKind::NonManifold => 3,
            }] += 1;
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn kinds_of_edges() {
        // Two triangles sharing 1–2 consistently, a third sharing 0–1 with flipped winding,
        // and a fourth also on 1–2 (non-manifold).
        let mesh = Mesh {
            positions: vec![DVec3::ZERO; 5],
            triangles: vec![[0, 1, 2], [2, 1, 3], [0, 1, 4], [1, 2, 4]],
        };
        let adj = Adjacency::build(&mesh);
        let kind = |a, b| {
            let e = adj.edges.iter().find(|e| e.a == a && e.b == b).unwrap();
            adj.kind(e)
        };
        assert_eq!(kind(1, 2), EdgeKind::NonManifold);
        assert_eq!(kind(0, 1), EdgeKind::Inconsistent);
        assert_eq!(kind(0, 2), EdgeKind::Border);
        let closed = Mesh {
            positions: vec![DVec3::ZERO; 4],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        };
        let adj = Adjacency::build(&closed);
        assert_eq!(adj.census(), [6, 0, 0, 0]);
    }
}
