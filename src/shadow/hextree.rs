//! The 4D dual-space hextree of Wallner §1.2 (16 children per node).
//!
//! A face plane (n, d) is a point in 4D dual space; a consistently wound manifold edge is
//! the segment between the dual points of its two faces. A light L = (x, y, z, w) is the
//! hyperplane {P : P · L = 0}: an edge is a silhouette edge exactly when its segment
//! crosses it. Each dual edge is stored in the smallest cell containing both ends; a query
//! skips every cell the hyperplane misses, bounding P · L over the cell by its min/max
//! corners chosen from the sign bits of L (Wallner Eq. 1.1).

use glam::DVec4;

use super::silhouette::{ManifoldEdge, Silhouette, SilhouetteMesh};
use super::Light;

/// Default maximum depth.
pub const DEFAULT_DEPTH: u32 = 7;

#[derive(Debug, Clone)]
struct Node {
    lo: DVec4,
    hi: DVec4,
    /// Edges stored here: `edges[first_edge..first_edge + edge_count]`.
    first_edge: u32,
    edge_count: u32,
    /// Children: `children[first_child..first_child + child_count]`.
    first_child: u32,
    child_count: u32,
}

/// A hextree over the manifold edges of a [`SilhouetteMesh`].
#[derive(Debug, Clone)]
pub struct Hextree {
    nodes: Vec<Node>,
    children: Vec<u32>,
    edges: Vec<ManifoldEdge>,
    depth: u32,
}

struct Builder<'a> {
    mesh: &'a SilhouetteMesh,
    max_depth: u32,
    nodes: Vec<Node>,
    child_lists: Vec<Vec<u32>>,
    edges: Vec<ManifoldEdge>,
}

fn child_of(p: DVec4, mid: DVec4) -> usize {
    (p.x >= mid.x) as usize
        | ((p.y >= mid.y) as usize) << 1
        | ((p.z >= mid.z) as usize) << 2
        | ((p.w >= mid.w) as usize) << 3
}

impl Builder<'_> {
    fn build(&mut self, lo: DVec4, hi: DVec4, items: Vec<u32>, depth: u32) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            lo,
            hi,
            first_edge: 0,
            edge_count: 0,
            first_child: 0,
            child_count: 0,
        });
        self.child_lists.push(Vec::new());
        let mid = (lo + hi) * 0.5;
        let mut here = Vec::new();
        let mut buckets: [Vec<u32>; 16] = Default::default();
        for i in items {
            let e = &self.mesh.manifold[i as usize];
            let p = self.mesh.planes[e.forward as usize];
            let q = self.mesh.planes[e.backward as usize];
            let (cp, cq) = (child_of(p, mid), child_of(q, mid));
            if depth >= self.max_depth || cp != cq {
                here.push(i);
            } else {
                buckets[cp].push(i);
            }
        }
        let first_edge = self.edges.len() as u32;
        self.edges
            .extend(here.iter().map(|&i| self.mesh.manifold[i as usize]));
        self.nodes[id as usize].first_edge = first_edge;
        self.nodes[id as usize].edge_count = here.len() as u32;
        for (c, bucket) in buckets.into_iter().enumerate() {
            if bucket.is_empty() {
                continue;
            }
            let pick =
                |k: usize, a: f64, m: f64, b: f64| if c >> k & 1 == 1 { (m, b) } else { (a, m) };
            let (x0, x1) = pick(0, lo.x, mid.x, hi.x);
            let (y0, y1) = pick(1, lo.y, mid.y, hi.y);
            let (z0, z1) = pick(2, lo.z, mid.z, hi.z);
            let (w0, w1) = pick(3, lo.w, mid.w, hi.w);
            let child = self.build(
                DVec4::new(x0, y0, z0, w0),
                DVec4::new(x1, y1, z1, w1),
                bucket,
                depth + 1,
            );
            self.child_lists[id as usize].push(child);
        }
        id
    }
}

impl Hextree {
    /// Builds the tree (once per mesh) with the given maximum depth.
    pub fn build(mesh: &SilhouetteMesh, max_depth: u32) -> Hextree {
        let mut lo = DVec4::splat(f64::INFINITY);
        let mut hi = DVec4::splat(f64::NEG_INFINITY);
        for p in &mesh.planes {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        // A margin keeps points off the outer faces.
        let pad = (hi - lo).max(DVec4::splat(1e-9)) * 1e-6;
        let mut b = Builder {
            mesh,
            max_depth,
            nodes: Vec::new(),
            child_lists: Vec::new(),
            edges: Vec::with_capacity(mesh.manifold.len()),
        };
        b.build(
            lo - pad,
            hi + pad,
            (0..mesh.manifold.len() as u32).collect(),
            0,
        );
        let mut children = Vec::new();
        for (n, list) in b.nodes.iter_mut().zip(&b.child_lists) {
            n.first_child = children.len() as u32;
            n.child_count = list.len() as u32;
            children.extend_from_slice(list);
        }
        Hextree {
            nodes: b.nodes,
            children,
            edges: b.edges,
            depth: max_depth,
        }
    }

    /// The maximum depth it was built with.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Silhouette edges for `light`: the same set as [`SilhouetteMesh::brute`].
    pub fn query(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        let l = mesh.light_in_frame(light);
        // Rounding in the corner bounds must not skip a cell holding a sign change.
        let tol = 1e-12 * (l.x.abs() + l.y.abs() + l.z.abs() + l.w.abs()) * 4.0;
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id as usize];
            // Min and max corners from the sign bits of L (Wallner Eq. 1.1).
            let pos = l.cmpge(DVec4::ZERO);
            let min_corner = DVec4::select(pos, n.lo, n.hi);
            let max_corner = DVec4::select(pos, n.hi, n.lo);
            let (dmin, dmax) = (min_corner.dot(l), max_corner.dot(l));
            if dmin > tol || dmax < -tol {
                continue;
            }
            let first = n.first_edge as usize;
            for e in &self.edges[first..first + n.edge_count as usize] {
                SilhouetteMesh::push_manifold(
                    &mut out,
                    e,
                    mesh.lit(e.forward, l),
                    mesh.lit(e.backward, l),
                );
            }
            let fc = n.first_child as usize;
            stack.extend_from_slice(&self.children[fc..fc + n.child_count as usize]);
        }
        mesh.other_edges(l, &mut out);
        Silhouette { edges: out }
    }
}
