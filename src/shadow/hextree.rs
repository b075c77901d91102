//! The 4D dual-space hextree of Wallner §1.2 (16 children per node).
//!
//! A face plane (n, d) is a point in 4D dual space; a consistently wound manifold edge is
//! the segment between the dual points of its two faces. A light L = (x, y, z, w) is the
//! hyperplane {P : P · L = 0}: an edge is a silhouette edge exactly when its segment
//! crosses it. Each dual edge is stored in the smallest cell containing both ends; a query
//! skips every cell the hyperplane misses, bounding P · L over the cell by its min/max
//! corners chosen from the sign bits of L (Wallner Eq. 1.1).
//!
//! Refinements keep the query ahead of a fast linear scan:
//! - the tree is *loose*: an edge goes to the child cell holding its dual segment's
//!   midpoint, down to leaves of at most [`LEAF_EDGES`] edges, instead of stopping at the
//!   first cell whose mid-plane its ends straddle (on a bumpy surface two thirds of the
//!   edges stopped at the root, where every query tests them);
//! - the bounds tested are the tight bounds of the dual points actually stored in a
//!   subtree (which is what makes a loose tree correct: a segment crossing the light's
//!   hyperplane lies inside its node's bounds, so the node straddles too);
//! - each node keeps its own run of face planes (a face once, however many of the node's
//!   edges it borders) and its edges index into it, so a query tests each plane once per
//!   node and reads memory in order;
//! - a query first judges, two levels down, how much of the tree the hyperplane meets and
//!   scans linearly when that is most of it (a scanned-like surface with 16 % silhouette
//!   edges), so it is never much slower than the scan.

use glam::Vec4;

use rustc_hash::FxHashMap as HashMap;

use super::silhouette::{Silhouette, SilhouetteMesh};
use super::Light;

/// Default maximum depth.
pub const DEFAULT_DEPTH: u32 = 5;

/// How many levels down [`Hextree::query`] judges whether the tree saves work.
pub const ESTIMATE_DEPTH: u32 = 3;

/// The largest fraction of the edges under the nodes a light's hyperplane meets (at
/// [`ESTIMATE_DEPTH`]) for which [`Hextree::query`] traverses the tree: an edge tested in
/// the tree costs about twice one of the linear scan (two inline dual points against one
/// shared face test), so beyond about half the scan is faster.
pub const FALLBACK_FRACTION: f64 = 0.5;

/// A node holding at most this many edges is a leaf.
pub const LEAF_EDGES: usize = 64;

/// A stored edge: its vertices and its two faces as indices into its node's own run of
/// face planes, so a query tests each plane of a node once and reads memory in order.
#[derive(Debug, Clone, Copy)]
struct TreeEdge {
    a: u32,
    b: u32,
    forward: u32,
    backward: u32,
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
    /// The planes of their faces: `faces[first_face..first_face + face_count]`.
    first_face: u32,
    face_count: u32,
    /// Children: `children[first_child..first_child + child_count]`.
    first_child: u32,
    child_count: u32,
    /// Edges stored in this subtree.
    subtree_edges: u32,
}

/// A hextree over the manifold edges of a [`SilhouetteMesh`].
#[derive(Debug, Clone)]
pub struct Hextree {
    nodes: Vec<Node>,
    children: Vec<u32>,
    edges: Vec<TreeEdge>,
    /// Per stored edge: whether it lies on an open surface (read for silhouette edges only).
    two_sided: Vec<bool>,
    faces: Vec<Vec4>,
    /// The most faces one node holds (the query's scratch size).
    max_faces: usize,
    depth: u32,
}

struct Builder<'a> {
    mesh: &'a SilhouetteMesh,
    max_depth: u32,
    nodes: Vec<Node>,
    child_lists: Vec<Vec<u32>>,
    edges: Vec<TreeEdge>,
    two_sided: Vec<bool>,
    faces: Vec<Vec4>,
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
            first_face: 0,
            face_count: 0,
            first_child: 0,
            child_count: 0,
            subtree_edges: 0,
        });
        self.child_lists.push(Vec::new());
        let mid = (lo + hi) * 0.5;
        let mut here = Vec::new();
        let mut buckets: [Vec<u32>; 16] = Default::default();
        if depth >= self.max_depth || items.len() <= LEAF_EDGES {
            here = items;
        } else {
            // Loose: an edge goes to the child holding its dual segment's midpoint, so no
            // edge sticks at a node because its ends straddle a cell's mid-plane.
            for i in items {
                let e = &self.mesh.manifold[i as usize];
                let p = self.mesh.planes[e.forward as usize];
                let q = self.mesh.planes[e.backward as usize];
                buckets[child_of((p + q) * 0.5, mid)].push(i);
            }
        }
        let first_edge = self.edges.len() as u32;
        let first_face = self.faces.len() as u32;
        let (mut own_lo, mut own_hi) = (Vec4::splat(f32::INFINITY), Vec4::splat(f32::NEG_INFINITY));
        let mut local: HashMap<u32, u32> = HashMap::default();
        for &i in &here {
            let edge = self.mesh.manifold[i as usize];
            let mut slot = |face: u32| -> u32 {
                *local.entry(face).or_insert_with(|| {
                    let p = self.mesh.planes[face as usize];
                    own_lo = own_lo.min(p);
                    own_hi = own_hi.max(p);
                    self.faces.push(p);
                    (self.faces.len() as u32) - 1 - first_face
                })
            };
            let (forward, backward) = (slot(edge.forward), slot(edge.backward));
            self.edges.push(TreeEdge {
                a: edge.a,
                b: edge.b,
                forward,
                backward,
            });
            self.two_sided
                .push(self.mesh.two_sided[edge.forward as usize]);
        }
        let node = &mut self.nodes[id as usize];
        node.first_edge = first_edge;
        node.edge_count = here.len() as u32;
        node.first_face = first_face;
        node.face_count = self.faces.len() as u32 - first_face;
        node.own_lo = own_lo;
        node.own_hi = own_hi;
        let (mut sub_lo, mut sub_hi) = (own_lo, own_hi);
        let mut subtree_edges = here.len() as u32;
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
            subtree_edges += self.nodes[child as usize].subtree_edges;
        }
        self.nodes[id as usize].lo = sub_lo;
        self.nodes[id as usize].hi = sub_hi;
        self.nodes[id as usize].subtree_edges = subtree_edges;
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
            two_sided: Vec::with_capacity(mesh.manifold.len()),
            faces: Vec::new(),
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
        let max_faces = b
            .nodes
            .iter()
            .map(|n| n.face_count as usize)
            .max()
            .unwrap_or(0);
        Hextree {
            nodes: b.nodes,
            children,
            two_sided: b.two_sided,
            edges: b.edges,
            max_faces,
            faces: b.faces,
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

    /// The fraction of the manifold edges a query for `light` would test at most, judged
    /// from the nodes down to `depth`: the edges under those the light's hyperplane meets.
    /// Stops counting once past `stop_fraction` (the answer is then only known to exceed it).
    pub fn estimate(
        &self,
        mesh: &SilhouetteMesh,
        light: &Light,
        depth: u32,
        stop_fraction: f64,
    ) -> f64 {
        let total = self.nodes[0].subtree_edges.max(1) as f64;
        let stop = (stop_fraction * total).ceil() as u64;
        let l = mesh.light_in_frame(light);
        let pos = l.cmpge(Vec4::ZERO);
        let straddles = |lo: Vec4, hi: Vec4| {
            Vec4::select(pos, lo, hi).dot(l) <= 0.0 && Vec4::select(pos, hi, lo).dot(l) >= 0.0
        };
        let mut edges = 0u64;
        let mut stack = vec![(0u32, 0u32)];
        while let Some((id, d)) = stack.pop() {
            let n = &self.nodes[id as usize];
            if !straddles(n.lo, n.hi) {
                continue;
            }
            if d == depth || n.child_count == 0 {
                edges += n.subtree_edges as u64;
            } else {
                edges += n.edge_count as u64;
            }
            if edges > stop {
                break; // enough to decide
            }
            if d == depth || n.child_count == 0 {
                continue;
            }
            let fc = n.first_child as usize;
            stack.extend(
                self.children[fc..fc + n.child_count as usize]
                    .iter()
                    .map(|&c| (c, d + 1)),
            );
        }
        edges as f64 / total
    }

    /// Silhouette edges for `light`: the same set as [`SilhouetteMesh::brute`]. When the
    /// light's hyperplane meets nodes holding more than [`FALLBACK_FRACTION`] of the edges
    /// (judged [`ESTIMATE_DEPTH`] levels down), the query is the linear scan, which then
    /// reads less memory.
    pub fn query(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        if self.estimate(mesh, light, ESTIMATE_DEPTH, FALLBACK_FRACTION) > FALLBACK_FRACTION {
            return mesh.brute(light);
        }
        self.traverse(mesh, light)
    }

    /// Silhouette edges for `light` by traversing the tree, whatever it meets.
    pub fn traverse(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        let l = mesh.light_in_frame(light);
        // Rounding in the corner bounds must not skip a box holding a sign change.
        let tol = 1e-5 * (l.x.abs() + l.y.abs() + l.z.abs() + l.w.abs());
        // Min and max corners from the sign bits of L (Wallner Eq. 1.1).
        let pos = l.cmpge(Vec4::ZERO);
        let straddles = |lo: Vec4, hi: Vec4| {
            Vec4::select(pos, lo, hi).dot(l) <= tol && Vec4::select(pos, hi, lo).dot(l) >= -tol
        };
        let mut out = Vec::new();
        let mut lit = vec![false; self.max_faces];
        let mut stack = vec![0u32];
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id as usize];
            if !straddles(n.lo, n.hi) {
                continue;
            }
            if n.edge_count > 0 && straddles(n.own_lo, n.own_hi) {
                let faces = &self.faces[n.first_face as usize..][..n.face_count as usize];
                for (flag, p) in lit.iter_mut().zip(faces) {
                    // The same expression as `SilhouetteMesh::lit` on the same numbers.
                    *flag = p.dot(l) > 0.0;
                }
                let first = n.first_edge as usize;
                let range = first..first + n.edge_count as usize;
                for (e, two_sided) in self.edges[range.clone()].iter().zip(&self.two_sided[range]) {
                    SilhouetteMesh::push_manifold(
                        &mut out,
                        [e.a, e.b],
                        lit[e.forward as usize],
                        lit[e.backward as usize],
                        || *two_sided,
                    );
                }
            }
            // Children in reverse, so they are visited in memory order.
            let fc = n.first_child as usize;
            stack.extend(self.children[fc..fc + n.child_count as usize].iter().rev());
        }
        mesh.other_edges(l, &mut out);
        Silhouette { edges: out }
    }
}
