//! The 4D dual-space hextree of Wallner §1.2 (16 children per node).
//!
//! A face plane (n, d) is a point in 4D dual space; a consistently wound manifold edge is
//! the segment between the dual points of its two faces. A light L = (x, y, z, w) is the
//! hyperplane {P : P · L = 0}: an edge is a silhouette edge exactly when its segment
//! crosses it. A query skips every cell the hyperplane misses, bounding P · L over the cell
//! by its min/max corners chosen from the sign bits of L (Wallner Eq. 1.1).
//!
//! Refinements keep the query ahead of a fast linear scan:
//! - the tree is *loose*: an edge goes to the child cell holding its dual segment's
//!   midpoint, down to leaves of at most [`LEAF_EDGES`] edges, instead of stopping at the
//!   first cell whose mid-plane its ends straddle (on a bumpy surface two thirds of the
//!   edges stopped at the root, where every query tests them);
//! - the bounds tested are the tight bounds of the dual points actually stored in a
//!   subtree (which is what makes a loose tree correct: a segment crossing the light's
//!   hyperplane lies inside its node's bounds, so the node straddles too);
//! - edges live in leaves only; a cell at the maximum depth holding more than
//!   [`LEAF_EDGES`] (faces on one plane share a dual point) is cut into leaves of that many;
//! - each leaf keeps its own run of face planes (a face once, however many of the leaf's
//!   edges it borders) and its edges index into it by a byte, so a query tests each plane
//!   once per leaf and reads memory in order;
//! - a query first judges, three levels down, how much of the tree the hyperplane meets and
//!   scans linearly when that is most of it (a scanned-like surface with 16 % silhouette
//!   edges), so it is never much slower than the scan; otherwise the traversal goes on from
//!   the nodes that judgement reached;
//! - the memory layout is made for a cold cache (a profile step runs the GPU and the volume
//!   code between two queries): a node is one 64-byte line, a node's children lie side by
//!   side (breadth-first numbering, so no child list), a leaf's planes and edges are
//!   prefetched as soon as its parent finds that it straddles and tested [`LEAF_LAG`]
//!   leaves later, a leaf whose faces all face one way is left at once, and a leaf's edges
//!   are tested without a branch per edge (about one in ten is a silhouette edge, which no
//!   branch predictor guesses).

use std::hint::select_unpredictable;

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

/// How many leaves a traversal finds before testing the first of them: their planes and
/// edges are loading meanwhile.
pub const LEAF_LAG: usize = 8;

/// A node holding at most this many edges is a leaf; a node at the maximum depth holding
/// more is cut into leaves of this many (so a leaf's faces fit a `u8` index).
pub const LEAF_EDGES: usize = 64;

const _: () = assert!(2 * LEAF_EDGES <= 256);

/// A stored edge: its vertices and its two faces as indices into its leaf's own run of
/// face planes (at most 2 × [`LEAF_EDGES`]), so a query tests each plane of a leaf once and
/// reads memory in order.
#[derive(Debug, Clone, Copy)]
struct TreeEdge {
    a: u32,
    b: u32,
    forward: u8,
    backward: u8,
    /// The edge lies on an open surface.
    two_sided: bool,
}

/// A node: one cache line. Edges live in leaves only (an inner node hands all of its edges
/// to its children).
#[derive(Debug, Clone)]
#[repr(C, align(64))]
struct Node {
    /// Tight bounds of every dual point stored in this subtree (tighter than the cell).
    lo: Vec4,
    hi: Vec4,
    /// Children: `nodes[first_child..first_child + child_count]`.
    first_child: u32,
    child_count: u32,
    /// A leaf's edges: `edges[first_edge..first_edge + edge_count]`.
    first_edge: u32,
    edge_count: u32,
    /// The planes of their faces: `faces[first_face..first_face + face_count]`.
    first_face: u32,
    face_count: u32,
    /// Edges stored in this subtree.
    subtree_edges: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 64);

/// A hextree over the manifold edges of a [`SilhouetteMesh`].
#[derive(Debug, Clone)]
pub struct Hextree {
    /// Breadth-first: a node's children are consecutive.
    nodes: Vec<Node>,
    /// Leaves' edges, in depth-first order of their leaves.
    edges: Vec<TreeEdge>,
    faces: Vec<Vec4>,
    depth: u32,
}

/// A node while building: depth-first, with its children listed.
struct BuildNode {
    node: Node,
    children: Vec<u32>,
}

struct Builder<'a> {
    mesh: &'a SilhouetteMesh,
    max_depth: u32,
    nodes: Vec<BuildNode>,
    edges: Vec<TreeEdge>,
    faces: Vec<Vec4>,
}

fn child_of(p: Vec4, mid: Vec4) -> usize {
    (p.x >= mid.x) as usize
        | ((p.y >= mid.y) as usize) << 1
        | ((p.z >= mid.z) as usize) << 2
        | ((p.w >= mid.w) as usize) << 3
}

/// The child cell `c` of the cell `lo..hi` (bit k of `c`: the upper half along axis k).
fn child_cell(c: usize, lo: Vec4, hi: Vec4) -> (Vec4, Vec4) {
    let mid = (lo + hi) * 0.5;
    let bit = |k: usize| (c >> k & 1) as f32;
    let upper = Vec4::new(bit(0), bit(1), bit(2), bit(3)).cmpeq(Vec4::ONE);
    (Vec4::select(upper, mid, lo), Vec4::select(upper, hi, mid))
}

impl Builder<'_> {
    fn build(&mut self, lo: Vec4, hi: Vec4, items: Vec<u32>, depth: u32) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(BuildNode {
            node: Node {
                lo: Vec4::splat(f32::INFINITY),
                hi: Vec4::splat(f32::NEG_INFINITY),
                first_child: 0,
                child_count: 0,
                first_edge: self.edges.len() as u32,
                edge_count: 0,
                first_face: self.faces.len() as u32,
                face_count: 0,
                subtree_edges: items.len() as u32,
            },
            children: Vec::new(),
        });
        if items.len() <= LEAF_EDGES {
            self.fill_leaf(id, &items);
            return id;
        }
        if depth >= self.max_depth {
            for chunk in items.chunks(LEAF_EDGES) {
                let child = self.build(lo, hi, chunk.to_vec(), depth + 1);
                self.nodes[id as usize].children.push(child);
            }
            self.bound_by_children(id);
            return id;
        }
        // Loose: an edge goes to the child holding its dual segment's midpoint, so no edge
        // sticks at a node because its ends straddle a cell's mid-plane.
        let mid = (lo + hi) * 0.5;
        let mut buckets: [Vec<u32>; 16] = Default::default();
        for i in items {
            let e = &self.mesh.manifold[i as usize];
            let p = self.mesh.planes[e.forward as usize];
            let q = self.mesh.planes[e.backward as usize];
            buckets[child_of((p + q) * 0.5, mid)].push(i);
        }
        for (c, bucket) in buckets.into_iter().enumerate() {
            if bucket.is_empty() {
                continue;
            }
            let (clo, chi) = child_cell(c, lo, hi);
            let child = self.build(clo, chi, bucket, depth + 1);
            self.nodes[id as usize].children.push(child);
        }
        self.bound_by_children(id);
        id
    }

    /// Sets an inner node's bounds to its children's.
    fn bound_by_children(&mut self, id: u32) {
        let (mut lo, mut hi) = (Vec4::splat(f32::INFINITY), Vec4::splat(f32::NEG_INFINITY));
        for &c in &self.nodes[id as usize].children {
            lo = lo.min(self.nodes[c as usize].node.lo);
            hi = hi.max(self.nodes[c as usize].node.hi);
        }
        let node = &mut self.nodes[id as usize].node;
        node.lo = lo;
        node.hi = hi;
    }

    /// Stores a leaf's edges and the planes of their faces (each face once).
    fn fill_leaf(&mut self, id: u32, items: &[u32]) {
        let first_face = self.faces.len() as u32;
        let (mut lo, mut hi) = (Vec4::splat(f32::INFINITY), Vec4::splat(f32::NEG_INFINITY));
        let mut local: HashMap<u32, u8> = HashMap::default();
        for &i in items {
            let edge = self.mesh.manifold[i as usize];
            let mut slot = |face: u32| -> u8 {
                *local.entry(face).or_insert_with(|| {
                    let p = self.mesh.planes[face as usize];
                    lo = lo.min(p);
                    hi = hi.max(p);
                    self.faces.push(p);
                    // At most two faces per edge, 2 × LEAF_EDGES ≤ 256.
                    (self.faces.len() as u32 - 1 - first_face) as u8
                })
            };
            let (forward, backward) = (slot(edge.forward), slot(edge.backward));
            self.edges.push(TreeEdge {
                a: edge.a,
                b: edge.b,
                forward,
                backward,
                two_sided: self.mesh.two_sided[edge.forward as usize],
            });
        }
        let node = &mut self.nodes[id as usize].node;
        node.edge_count = items.len() as u32;
        node.face_count = self.faces.len() as u32 - first_face;
        node.lo = lo;
        node.hi = hi;
    }

    /// The nodes numbered breadth-first, so that each node's children are consecutive.
    fn breadth_first(self) -> Vec<Node> {
        let mut order = vec![0u32];
        let mut nodes = Vec::with_capacity(self.nodes.len());
        while let Some(&old) = order.get(nodes.len()) {
            let built = &self.nodes[old as usize];
            let mut node = built.node.clone();
            node.first_child = order.len() as u32;
            node.child_count = built.children.len() as u32;
            order.extend_from_slice(&built.children);
            nodes.push(node);
        }
        nodes
    }
}

/// A light in the tree's frame and the test of a node's bounds against its hyperplane.
struct Probe {
    l: Vec4,
    tol: f32,
}

impl Probe {
    fn new(mesh: &SilhouetteMesh, light: &Light) -> Probe {
        let l = mesh.light_in_frame(light);
        Probe {
            l,
            // Rounding in the corner bounds must not skip a box holding a sign change.
            tol: 1e-5 * (l.x.abs() + l.y.abs() + l.z.abs() + l.w.abs()),
        }
    }

    /// Whether the hyperplane meets `node`'s bounds.
    #[inline]
    fn straddles(&self, node: &Node) -> bool {
        // Min and max corners from the sign bits of L (Wallner Eq. 1.1).
        let pos = self.l.cmpge(Vec4::ZERO);
        Vec4::select(pos, node.lo, node.hi).dot(self.l) <= self.tol
            && Vec4::select(pos, node.hi, node.lo).dot(self.l) >= -self.tol
    }
}

/// A query's scratch for one leaf, indexed by a `u8` and by masked counts, so no index is
/// checked in the loops.
struct LeafScratch {
    /// Whether each of the leaf's faces is lit.
    lit: [bool; 256],
    /// The leaf's silhouette edges, and past them anything.
    found: [[u32; 2]; 2 * LEAF_EDGES],
}

/// Where a query stands after judging the top levels.
struct Frontier {
    /// Straddling nodes to go on from, in memory order.
    nodes: Vec<u32>,
    /// The edges under them, or a count past the stop when the judgement stopped early.
    edges: u64,
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
            edges: Vec::with_capacity(mesh.manifold.len()),
            faces: Vec::new(),
        };
        b.build(
            lo - pad,
            hi + pad,
            (0..mesh.manifold.len() as u32).collect(),
            0,
        );
        let (edges, faces) = (std::mem::take(&mut b.edges), std::mem::take(&mut b.faces));
        let nodes = b.breadth_first();
        Hextree {
            nodes,
            edges,
            faces,
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

    fn children(&self, n: &Node) -> std::ops::Range<usize> {
        n.first_child as usize..(n.first_child + n.child_count) as usize
    }

    /// Edges stored at each depth (diagnostics).
    pub fn edges_per_level(&self) -> Vec<usize> {
        // A node at the maximum depth may be cut into leaves one level further down.
        let mut out = vec![0; self.depth as usize + 2];
        let mut stack = vec![(0usize, 0usize)];
        while let Some((id, d)) = stack.pop() {
            let n = &self.nodes[id];
            out[d] += n.edge_count as usize;
            stack.extend(self.children(n).map(|c| (c, d + 1)));
        }
        out
    }

    /// (nodes visited, edges tested) by a traversal (diagnostics).
    pub fn query_stats(&self, mesh: &SilhouetteMesh, light: &Light) -> (usize, usize) {
        let probe = Probe::new(mesh, light);
        let (mut nodes, mut edges) = (0, 0);
        let mut stack = vec![0usize];
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id];
            if !probe.straddles(n) {
                continue;
            }
            nodes += 1;
            edges += n.edge_count as usize;
            stack.extend(self.children(n));
        }
        (nodes, edges)
    }

    /// Judges the nodes down to `depth` level by level: the straddling nodes at `depth` and
    /// the straddling leaves above it, with the edges under them. Stops counting once past
    /// `stop` edges (the answer is then only known to exceed it).
    fn frontier(&self, probe: &Probe, depth: u32, stop: u64) -> Frontier {
        let mut level: Vec<u32> = Vec::new();
        if probe.straddles(&self.nodes[0]) {
            level.push(0);
        }
        let mut leaves = Vec::new();
        let mut edges = 0u64;
        for _ in 0..depth {
            let mut next = Vec::with_capacity(level.len() * 4);
            for &id in &level {
                let n = &self.nodes[id as usize];
                if n.child_count == 0 {
                    leaves.push(id);
                    edges += n.edge_count as u64;
                    continue;
                }
                next.extend(
                    self.children(n)
                        .filter(|&c| probe.straddles(&self.nodes[c]))
                        .map(|c| c as u32),
                );
            }
            if edges > stop {
                return Frontier {
                    nodes: leaves,
                    edges,
                };
            }
            level = next;
        }
        for &id in &level {
            edges += self.nodes[id as usize].subtree_edges as u64;
            if edges > stop {
                break;
            }
        }
        leaves.extend(level);
        Frontier {
            nodes: leaves,
            edges,
        }
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
        self.judge(&Probe::new(mesh, light), depth, stop_fraction).1
    }

    /// [`Hextree::frontier`] with its edge count as a fraction of all the manifold edges.
    fn judge(&self, probe: &Probe, depth: u32, stop_fraction: f64) -> (Frontier, f64) {
        let total = self.nodes[0].subtree_edges.max(1) as f64;
        let stop = (stop_fraction * total).ceil() as u64;
        let frontier = self.frontier(probe, depth, stop);
        let fraction = frontier.edges as f64 / total;
        (frontier, fraction)
    }

    /// Silhouette edges for `light`: the same set as [`SilhouetteMesh::brute`]. When the
    /// light's hyperplane meets nodes holding more than [`FALLBACK_FRACTION`] of the edges
    /// (judged [`ESTIMATE_DEPTH`] levels down), the query is the linear scan, which then
    /// reads less memory; otherwise the traversal goes on from the nodes judged.
    pub fn query(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        let probe = Probe::new(mesh, light);
        let (frontier, fraction) = self.judge(&probe, ESTIMATE_DEPTH, FALLBACK_FRACTION);
        if fraction > FALLBACK_FRACTION {
            return mesh.brute(light);
        }
        self.walk(mesh, &probe, frontier.nodes)
    }

    /// Silhouette edges for `light` by traversing the tree, whatever it meets.
    pub fn traverse(&self, mesh: &SilhouetteMesh, light: &Light) -> Silhouette {
        let probe = Probe::new(mesh, light);
        let frontier = self.frontier(&probe, 0, u64::MAX);
        self.walk(mesh, &probe, frontier.nodes)
    }

    /// Traverses depth-first from `start` (straddling nodes, first visited first).
    fn walk(&self, mesh: &SilhouetteMesh, probe: &Probe, start: Vec<u32>) -> Silhouette {
        let mut out = Vec::new();
        let mut scratch = LeafScratch {
            lit: [false; 256],
            found: [[0; 2]; 2 * LEAF_EDGES],
        };
        for &id in &start {
            self.prefetch_below(&self.nodes[id as usize]);
        }
        let mut stack = start;
        stack.reverse();
        // Leaves found, tested [`LEAF_LAG`] leaves later, when their data has arrived.
        let mut pending = std::collections::VecDeque::with_capacity(LEAF_LAG);
        while let Some(id) = stack.pop() {
            let n = &self.nodes[id as usize];
            if n.child_count == 0 {
                if pending.len() == LEAF_LAG {
                    if let Some(first) = pending.pop_front() {
                        let leaf = &self.nodes[first as usize];
                        self.test_leaf(leaf, probe.l, &mut scratch, &mut out);
                    }
                }
                pending.push_back(id);
                continue;
            }
            // In reverse, so that they are visited in memory order. Their own children
            // (or a leaf's data) were asked for when this node was pushed.
            for c in self.children(n).rev() {
                let child = &self.nodes[c];
                if probe.straddles(child) {
                    self.prefetch_below(child);
                    stack.push(c as u32);
                }
            }
        }
        for id in pending {
            self.test_leaf(&self.nodes[id as usize], probe.l, &mut scratch, &mut out);
        }
        mesh.other_edges(probe.l, &mut out);
        Silhouette { edges: out }
    }

    /// Starts loading what a visit to `n` reads next: a leaf's planes and edges, an inner
    /// node's children.
    #[inline]
    fn prefetch_below(&self, n: &Node) {
        if n.edge_count > 0 {
            prefetch_lines(&self.faces[n.first_face as usize..][..n.face_count as usize]);
            prefetch_lines(&self.edges[n.first_edge as usize..][..n.edge_count as usize]);
        } else {
            prefetch_lines(&self.nodes[self.children(n)]);
        }
    }

    /// Appends a leaf's silhouette edges: the rule of [`SilhouetteMesh::push_manifold`]
    /// (a→b when the forward face is lit, twice on an open surface), written without a
    /// branch: every edge is stored and the end advances only past silhouette edges.
    #[inline]
    fn test_leaf(&self, n: &Node, l: Vec4, scratch: &mut LeafScratch, out: &mut Vec<[u32; 2]>) {
        let LeafScratch { lit, found } = scratch;
        let faces = &self.faces[n.first_face as usize..][..n.face_count as usize];
        let (mut any_lit, mut all_lit) = (false, true);
        for (flag, p) in lit.iter_mut().zip(faces) {
            // The same expression as `SilhouetteMesh::lit` on the same numbers.
            *flag = p.dot(l) > 0.0;
            any_lit |= *flag;
            all_lit &= *flag;
        }
        if any_lit == all_lit {
            return; // every face on one side: no silhouette edge here
        }
        let edges = &self.edges[n.first_edge as usize..][..n.edge_count as usize];
        let mut end = 0;
        for e in edges {
            let fw = lit[e.forward as usize];
            let bw = lit[e.backward as usize];
            // About one edge in ten is a silhouette edge: no branch predictor guesses which.
            let edge = select_unpredictable(fw, [e.a, e.b], [e.b, e.a]);
            // Edge k's copies land at most at 2k and 2k + 1 (< 2 × LEAF_EDGES).
            found[end % (2 * LEAF_EDGES)] = edge;
            found[(end + 1) % (2 * LEAF_EDGES)] = edge;
            end += select_unpredictable(fw != bw, 1 + e.two_sided as usize, 0);
        }
        out.extend_from_slice(&found[..end]);
    }
}

/// Asks the CPU to start loading every cache line of `xs` (a no-op where unsupported).
#[inline(always)]
fn prefetch_lines<T>(xs: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        let p = xs.as_ptr().cast::<i8>();
        for offset in (0..std::mem::size_of_val(xs)).step_by(64) {
            // SAFETY: a prefetch is only a hint; it reads nothing and never faults.
            unsafe {
                use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
                _mm_prefetch(p.wrapping_add(offset), _MM_HINT_T0);
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = xs;
}
