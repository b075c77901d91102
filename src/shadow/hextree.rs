//! The 4D dual-space hextree of Wallner §1.2 (16 children per node).
//!
//! A face plane (n, d) is a point in 4D dual space; a consistently wound manifold edge is
//! the segment between the dual points of its two faces. A light L = (x, y, z, w) is the
//! hyperplane {P : P · L = 0}: an edge is a silhouette edge exactly when its segment
//! crosses it. Each dual edge is stored in the smallest cell containing both ends; a query
//! skips every cell the hyperplane misses, bounding P · L over the cell by its min/max
//! corners chosen from the sign bits of L (Wallner Eq. 1.1).
//!
//! Two refinements keep the query ahead of a fast linear scan: the bounds tested are the
//! tight bounds of the dual points actually stored in a subtree (and, separately, of a
//! node's own edges) rather than the cell, and each stored edge carries its two dual points
//! inline so a query reads memory in order.

use glam::Vec4;

use super::silhouette::{ManifoldEdge, Silhouette, SilhouetteMesh};
use super::Light;

/// Default maximum depth.
pub const DEFAULT_DEPTH: u32 = 5;

/// A stored dual edge: both dual points inline, so a query reads memory in order.
#[derive(Debug, Clone, Copy)]
struct TreeEdge {
    p: Vec4,
    q: Vec4,
    edge: ManifoldEdge,
}

#[derive(Debug, Clone)]
struct Node {
    /// Tight bounds of every dual point stored in this subtree (tighter than the cell).
    lo: Vec4,
    hi: Vec4,
    /// Tight bounds of the dual points of this node's own edges.
    own_lo: Vec4,
    own_hi: Vec4,
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
    edges: Vec<TreeEdge>,
    depth: u32,
}

struct Builder<'a> {
    mesh: &'a SilhouetteMesh,
    max_depth: u32,
    nodes: Vec<Node>,
    child_lists: Vec<Vec<u32>>,
    edges: Vec<TreeEdge>,
}

fn child_of(p: Vec4, mid: Vec4) -> usize {
    (p.x >= mid.x) as usize
        | ((p.y >= mid.y) as usize) << 1
        | ((p.z >= mid.z) as usize) << 2
        | ((p.w >= mid.w) as usize) << 3
}

impl Builder<'_> {
    fn build(&mut self, lo: Vec4, hi: Vec4, items: Vec<u32>, depth: u32) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            lo: Vec4::splat(f32::INFINITY),
            hi: Vec4::splat(f32::NEG_INFINITY),
            own_lo: Vec4::splat(f32::INFINITY),
            own_hi: Vec4::splat(f32::NEG_INFINITY),
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
        let (mut own_lo, mut own_hi) = (Vec4::splat(f32::INFINITY), Vec4::splat(f32::NEG_INFINITY));
        for &i in &here {
            let edge = self.mesh.manifold[i as usize];
            let p = self.mesh.planes[edge.forward as usize];
            let q = self.mesh.planes[edge.backward as usize];
            own_lo = own_lo.min(p).min(q);
            own_hi = own_hi.max(p).max(q);
            self.edges.push(TreeEdge { p, q, edge });
        }
        let node = &mut self.nodes[id as usize];
        node.first_edge = first_edge;
        node.edge_count = here.len() as u32;
        node.own_lo = own_lo;
        node.own_hi = own_hi;
        let (mut sub_lo, mut sub_hi) = (own_lo, own_hi);
        for (c, bucket) in buckets.into_iter().enumerate() {
            if bucket.is_empty() {
                continue;
            }
            let pick =
                |k: usize, a: f32, m: f32, b: f32| if c >> k & 1 == 1 { (m, b) } else { (a, m) };
            let (x0, x1) = pick(0, lo.x, mid.x, hi.x);
            let (y0, y1) = pick(1, lo.y, mid.y, hi.y);
            let (z0, z1) = pick(2, lo.z, mid.z, hi.z);
            let (w0, w1) = pick(3, lo.w, mid.w, hi.w);
            let child = self.build(
                Vec4::new(x0, y0, z0, w0),
                Vec4::new(x1, y1, z1, w1),
                bucket,
                depth + 1,
            );
            self.child_lists[id as usize].push(child);
            sub_lo = sub_lo.min(self.nodes[child as usize].lo);
            sub_hi = sub_hi.max(self.nodes[child as usize].hi);
        }
        self.nodes[id as usize].lo = sub_lo;
        self.nodes[id as usize].hi = sub_hi;
        id
    }
}

impl Hextree {
    /// Builds the tree (once per mesh) with the given maximum depth.
    pub fn build(mesh: &SilhouetteMesh, max_depth: u32) -> Hextree {
        let mut lo = Vec4::splat(f32::INFINITY);
        let mut hi = Vec4::splat(f32::NEG_INFINITY);
        for p in &mesh.planes {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        // A margin keeps points off the outer faces.
        let pad = (hi - lo).max(Vec4::splat(1e-6)) * 1e-4;
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

    /// Edges stored at each depth (diagnostics).
    pub fn edges_per_level(&self) -> Vec<usize> {
        let mut out = vec![0; self.depth as usize + 1];
        let mut stack = vec![(0u32, 0usize)];
        while let Some((id, d)) = stack.pop() {
            let n = &self.nodes[id as usize];
            out[d] += n.edge_count as usize;
            let fc = n.first_child as usize;
            for &c in &self.children[fc..fc + n.child_count as usize] {
                stack.push((c, d + 1));
            }
        }
        out
    }

    /// (nodes visited, edges tested) by a query (diagnostics).
    pub fn query_stats(&self, mesh: &SilhouetteMesh, light: &Light) -> (usize, usize) {
        let l = mesh.light_in_frame(light);
        let pos = l.cmpge(Vec4::ZERO);
        let straddles = |lo: Vec4, hi: Vec4| {
            Vec4::select(pos, lo, hi).dot(l) <= 0.0 && Vec4::select(pos, hi, lo).dot(l) >= 0.0
        };
        let (mut nodes, mut edges) = (0, 0);
        let mut stack = vec![0u32];
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id as usize];
            if !straddles(n.lo, n.hi) {
                continue;
            }
            nodes += 1;
            if straddles(n.own_lo, n.own_hi) {
                edges += n.edge_count as usize;
            }
            let fc = n.first_child as usize;
            stack.extend_from_slice(&self.children[fc..fc + n.child_count as usize]);
        }
        (nodes, edges)
    }

    /// Silhouette edges for `light`: the same set as [`SilhouetteMesh::brute`].
    pub fn query(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        let l = mesh.light_in_frame(light);
        // Rounding in the corner bounds must not skip a box holding a sign change.
        let tol = 1e-5 * (l.x.abs() + l.y.abs() + l.z.abs() + l.w.abs());
        // Min and max corners from the sign bits of L (Wallner Eq. 1.1).
        let pos = l.cmpge(Vec4::ZERO);
        let straddles = |lo: Vec4, hi: Vec4| {
            Vec4::select(pos, lo, hi).dot(l) <= tol && Vec4::select(pos, hi, lo).dot(l) >= -tol
        };
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id as usize];
            if !straddles(n.lo, n.hi) {
                continue;
            }
            if n.edge_count > 0 && straddles(n.own_lo, n.own_hi) {
                let first = n.first_edge as usize;
                for e in &self.edges[first..first + n.edge_count as usize] {
                    // The same expression as `SilhouetteMesh::lit` on the same numbers.
                    SilhouetteMesh::push_manifold(
                        &mut out,
                        &e.edge,
                        e.p.dot(l) > 0.0,
                        e.q.dot(l) > 0.0,
                    );
                }
            }
            let fc = n.first_child as usize;
            stack.extend_from_slice(&self.children[fc..fc + n.child_count as usize]);
        }
        mesh.other_edges(l, &mut out);
        Silhouette { edges: out }
    }
}
