//! The face-cluster hierarchy of Edström §4.2 (after Garland's face clustering and
//! Willmott's face-cluster radiosity): every triangle starts as a cluster; the dual edge
//! (two adjacent clusters of one material) whose merge costs least is collapsed, again and
//! again, until each connected surface of one material is one root. The cost is Willmott's
//! (Edström Eq. 4.8): `(E_fit + k · A) · p² / |S|` — the merged cluster's planarity fit
//! error, plus `k` times its area, normalised by its perimeter squared over its summed area
//! normal (compact clusters with consistently oriented faces first). Each cluster has an
//! oriented bounding box around its summed area normal. The geometry is never changed:
//! clusters only group triangles.

pub mod fit;
pub mod obb;

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

use glam::DVec3;

use crate::geometry::Mesh;
pub use fit::FitQuadric;
pub use obb::Obb;

/// How the hierarchy is built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterSettings {
    /// Willmott's `k`: how much balanced (compact, even-sized) clusters count against
    /// planarity. Small values keep clusters planar longer.
    pub k: f64,
}

impl Default for ClusterSettings {
    fn default() -> Self {
        ClusterSettings { k: 0.01 }
    }
}

/// A cluster is planar when its corners lie within this fraction of a texel of their
/// least-squares plane (root mean square) …
pub const PLANAR_RMS_TEXELS: f64 = 0.01;
/// … and its faces' normals agree: |Σ area normal| / Σ area at least this (about 2.6°).
pub const PLANAR_NORMALS: f64 = 0.999;

/// The hierarchy cut where clusters stop being planar: the light map's charts and the
/// shooters of `--hierarchy clusters`.
#[derive(Debug, Clone, Default)]
pub struct PlanarClusters {
    /// The whole hierarchy.
    pub tree: FaceClusters,
    /// From each root, the largest planar clusters; every triangle lies in exactly one.
    pub cut: Vec<u32>,
    /// Per node, the largest texel side of its triangles, metres.
    pub texel: Vec<f64>,
}

impl PlanarClusters {
    /// Builds the hierarchy of `mesh` (triangle `t` of material `materials[t]` and texel
    /// side `texel[t]` metres) and cuts it where clusters stop being planar.
    pub fn new(mesh: &Mesh, materials: &[usize], texel: &[f64]) -> PlanarClusters {
        let tree = FaceClusters::build(mesh, materials, ClusterSettings::default());
        let mut node_texel = vec![0.0f64; tree.nodes.len()];
        // Children come before their parents.
        for k in 0..tree.nodes.len() {
            node_texel[k] = match tree.nodes[k].children {
                None => texel[tree.triangles(k as u32)[0] as usize],
                Some([a, b]) => node_texel[a as usize].max(node_texel[b as usize]),
            };
        }
        let mut cut = Vec::new();
        let mut stack: Vec<u32> = tree.roots.clone();
        while let Some(node) = stack.pop() {
            let c = &tree.nodes[node as usize];
            let planar = c.fit_error.sqrt() <= PLANAR_RMS_TEXELS * node_texel[node as usize]
                && c.area_normal.length() >= PLANAR_NORMALS * c.area;
            match c.children {
                Some(children) if !planar => stack.extend(children),
                _ => cut.push(node),
            }
        }
        PlanarClusters {
            tree,
            cut,
            texel: node_texel,
        }
    }

    /// Per triangle, the index in [`PlanarClusters::cut`] of its cluster.
    pub fn cluster_of_triangle(&self) -> Vec<u32> {
        let mut of = vec![u32::MAX; self.tree.order.len()];
        for (k, &node) in self.cut.iter().enumerate() {
            for &t in self.tree.triangles(node) {
                of[t as usize] = k as u32;
            }
        }
        of
    }
}

/// One cluster of the hierarchy.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceCluster {
    /// The two clusters merged into this one (`None` for a leaf: one triangle).
    pub children: Option<[u32; 2]>,
    /// The cluster this one was merged into (`None` for a root).
    pub parent: Option<u32>,
    /// Its triangles are `order[first..first + count]` of [`FaceClusters::order`].
    pub first: u32,
    /// How many triangles it holds.
    pub count: u32,
    /// Material of all its triangles.
    pub material: usize,
    /// Area, m².
    pub area: f64,
    /// Summed area-weighted normal S (Eq. 4.9), m².
    pub area_normal: DVec3,
    /// Perimeter, metres (edges shared with no other triangle of the cluster).
    pub perimeter: f64,
    /// Mean squared distance of its triangles' corners to their least-squares plane, m².
    pub fit_error: f64,
    /// The cost of the merge that made it (0 for a leaf).
    pub cost: f64,
    /// Bounding box: around the leaf's corners, or around the children's boxes.
    pub obb: Obb,
    quadric: FitQuadric,
}

/// The hierarchy over a mesh: leaves `0..triangles` are the triangles (node `t` holds
/// triangle `t`), merged clusters follow in the order they were made.
#[derive(Debug, Clone, Default)]
pub struct FaceClusters {
    /// Every cluster, leaves first.
    pub nodes: Vec<FaceCluster>,
    /// The roots: one per connected surface of one material.
    pub roots: Vec<u32>,
    /// Triangle indices, each cluster's contiguous (depth first from each root).
    pub order: Vec<u32>,
}

/// A candidate merge in the priority queue (cheapest first).
#[derive(Debug, Clone, Copy)]
struct Candidate {
    cost: f64,
    a: u32,
    b: u32,
}

impl PartialEq for Candidate {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Candidate {
    /// Reversed on cost, so the max-heap pops the cheapest; ties by the pair (stable).
    fn cmp(&self, o: &Self) -> Ordering {
        o.cost
            .total_cmp(&self.cost)
            .then_with(|| (o.a, o.b).cmp(&(self.a, self.b)))
    }
}

/// Per triangle, the other triangles of the same material sharing an edge with it, and
/// the shared length. Corners are matched by position (bit for bit), so a mesh whose
/// objects repeat vertices is joined where its surfaces touch.
fn dual_graph(mesh: &Mesh, materials: &[usize]) -> Vec<Vec<(u32, f64)>> {
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let ids: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let n = weld.len() as u32;
            *weld.entry(p.to_array().map(f64::to_bits)).or_insert(n)
        })
        .collect();
    // Per welded edge: its length and the triangles along it.
    let mut edges: HashMap<(u32, u32), (f64, Vec<u32>)> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (i, j) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
            let (a, b) = (ids[i], ids[j]);
            if a != b {
                let length = mesh.positions[i].distance(mesh.positions[j]);
                let e = edges
                    .entry((a.min(b), a.max(b)))
                    .or_insert((length, Vec::new()));
                e.1.push(t as u32);
            }
        }
    }
    let mut adjacent = vec![Vec::new(); mesh.triangles.len()];
    for (length, faces) in edges.values() {
        for (i, &f) in faces.iter().enumerate() {
            for &g in &faces[i + 1..] {
                if f != g && materials[f as usize] == materials[g as usize] {
                    add_length(&mut adjacent[f as usize], g, *length);
                    add_length(&mut adjacent[g as usize], f, *length);
                }
            }
        }
    }
    // The edge map's order is random: sort, so the same mesh always clusters the same.
    for list in &mut adjacent {
        list.sort_by_key(|e| e.0);
    }
    adjacent
}

/// Adds `length` to the entry for `to` in `list` (a new entry when there is none).
fn add_length(list: &mut Vec<(u32, f64)>, to: u32, length: f64) {
    match list.iter_mut().find(|(n, _)| *n == to) {
        Some(e) => e.1 += length,
        None => list.push((to, length)),
    }
}

/// The connected surfaces of one material of `mesh` (what the roots of its hierarchy
/// cover), found from the dual graph without building the hierarchy: each surface's
/// triangles ascending, the surfaces in order, as [`FaceClusters::root_surfaces`] lists
/// them.
pub fn connected_surfaces(mesh: &Mesh, materials: &[usize]) -> Vec<Vec<u32>> {
    let adjacent = dual_graph(mesh, materials);
    let mut seen = vec![false; mesh.triangles.len()];
    let mut surfaces = Vec::new();
    for start in 0..mesh.triangles.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let (mut surface, mut stack) = (Vec::new(), vec![start as u32]);
        while let Some(t) = stack.pop() {
            surface.push(t);
            for &(u, _) in &adjacent[t as usize] {
                if !std::mem::replace(&mut seen[u as usize], true) {
                    stack.push(u);
                }
            }
        }
        surface.sort_unstable();
        surfaces.push(surface);
    }
    surfaces.sort();
    surfaces
}

impl FaceClusters {
    /// Builds the hierarchy of `mesh`, whose triangle `t` has material `materials[t]`.
    pub fn build(mesh: &Mesh, materials: &[usize], settings: ClusterSettings) -> FaceClusters {
        assert_eq!(
            materials.len(),
            mesh.triangles.len(),
            "one material per triangle"
        );
        let n = mesh.triangles.len();
        let mut nodes: Vec<FaceCluster> = (0..n).map(|t| leaf(mesh, t, materials[t])).collect();
        let mut neighbours = dual_graph(mesh, materials);
        let mut alive = vec![true; n];
        let mut heap = BinaryHeap::new();
        for (a, list) in neighbours.iter().enumerate() {
            for &(b, shared) in list {
                if (a as u32) < b {
                    let cost = merge_cost(&nodes[a], &nodes[b as usize], shared, settings);
                    heap.push(Candidate {
                        cost,
                        a: a as u32,
                        b,
                    });
                }
            }
        }
        while let Some(Candidate { cost, a, b }) = heap.pop() {
            if !(alive[a as usize] && alive[b as usize]) {
                continue;
            }
            let c = nodes.len() as u32;
            let shared = shared_length(&neighbours[a as usize], b);
            let merged = merge(&nodes[a as usize], &nodes[b as usize], [a, b], shared, cost);
            nodes[a as usize].parent = Some(c);
            nodes[b as usize].parent = Some(c);
            alive[a as usize] = false;
            alive[b as usize] = false;
            nodes.push(merged);
            alive.push(true);
            // c's neighbours: a's and b's but a and b, lengths summed. Every list stays
            // sorted by cluster: c, the newest, is pushed at the end of its neighbours'.
            let list = merge_sorted(&neighbours[a as usize], &neighbours[b as usize], [a, b]);
            for &(m, l) in &list {
                let theirs = &mut neighbours[m as usize];
                theirs.retain(|&(x, _)| x != a && x != b);
                theirs.push((c, l));
                let cost = merge_cost(&nodes[c as usize], &nodes[m as usize], l, settings);
                heap.push(Candidate {
                    cost,
                    a: c.min(m),
                    b: c.max(m),
                });
            }
            neighbours[a as usize] = Vec::new();
            neighbours[b as usize] = Vec::new();
            neighbours.push(list);
        }
        let roots: Vec<u32> = (0..nodes.len() as u32)
            .filter(|&k| alive[k as usize])
            .collect();
        let order = number_depth_first(&mut nodes, &roots);
        FaceClusters {
            nodes,
            roots,
            order,
        }
    }

    /// The triangles of cluster `node`.
    pub fn triangles(&self, node: u32) -> &[u32] {
        let c = &self.nodes[node as usize];
        &self.order[c.first as usize..(c.first + c.count) as usize]
    }

    /// Each root's triangles, sorted, the roots in the order of their first triangle:
    /// the connected one-material surfaces the hierarchy found.
    pub fn root_surfaces(&self) -> Vec<Vec<u32>> {
        let mut roots: Vec<Vec<u32>> = self
            .roots
            .iter()
            .map(|&r| {
                let mut t = self.triangles(r).to_vec();
                t.sort_unstable();
                t
            })
            .collect();
        roots.sort();
        roots
    }

    /// The deepest leaf's distance from its root (0 when every root is a leaf).
    pub fn depth(&self) -> usize {
        let mut depth = vec![0usize; self.nodes.len()];
        // Parents come after their children, so a reverse sweep sees parents first.
        for k in (0..self.nodes.len()).rev() {
            if let Some(p) = self.nodes[k].parent {
                depth[k] = depth[p as usize] + 1;
            }
        }
        depth.into_iter().max().unwrap_or(0)
    }
}

fn shared_length(list: &[(u32, f64)], to: u32) -> f64 {
    list.binary_search_by_key(&to, |e| e.0)
        .map_or(0.0, |k| list[k].1)
}

/// The union of two neighbour lists sorted by cluster, lengths of common entries summed,
/// `skip` left out.
fn merge_sorted(x: &[(u32, f64)], y: &[(u32, f64)], skip: [u32; 2]) -> Vec<(u32, f64)> {
    let mut out = Vec::with_capacity(x.len() + y.len());
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        let next = match (x.get(i), y.get(j)) {
            (Some(&(m, l)), Some(&(n, k))) if m == n => {
                (i, j) = (i + 1, j + 1);
                (m, l + k)
            }
            (Some(&e), Some(&(n, _))) if e.0 < n => {
                i += 1;
                e
            }
            (Some(&e), None) => {
                i += 1;
                e
            }
            (_, Some(&e)) => {
                j += 1;
                e
            }
            (None, None) => break,
        };
        if !skip.contains(&next.0) {
            out.push(next);
        }
    }
    out
}

/// Triangle `t` as a leaf.
fn leaf(mesh: &Mesh, t: usize, material: usize) -> FaceCluster {
    let corners = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
    let s = mesh.face_normal(t) * 0.5;
    let quadric = FitQuadric::of_points(&corners);
    FaceCluster {
        children: None,
        parent: None,
        first: 0,
        count: 1,
        material,
        area: s.length(),
        area_normal: s,
        perimeter: (0..3)
            .map(|k| corners[k].distance(corners[(k + 1) % 3]))
            .sum(),
        fit_error: quadric.fit_error(),
        cost: 0.0,
        obb: Obb::around(&corners, s),
        quadric,
    }
}

/// Eq. 4.8 for merging `a` and `b`, which share edges of total length `shared`.
fn merge_cost(a: &FaceCluster, b: &FaceCluster, shared: f64, settings: ClusterSettings) -> f64 {
    let q = a.quadric + b.quadric;
    let area = a.area + b.area;
    let s = (a.area_normal + b.area_normal).length();
    let p = (a.perimeter + b.perimeter - 2.0 * shared).max(0.0);
    if s <= 1e-12 * area.max(f64::MIN_POSITIVE) {
        // Faces that cancel out (the two sides of a sheet): merged last.
        return f64::INFINITY;
    }
    (q.fit_error() + settings.k * area) * p * p / s
}

fn merge(a: &FaceCluster, b: &FaceCluster, ids: [u32; 2], shared: f64, cost: f64) -> FaceCluster {
    let quadric = a.quadric + b.quadric;
    let area_normal = a.area_normal + b.area_normal;
    let corners: Vec<DVec3> = a.obb.corners().into_iter().chain(b.obb.corners()).collect();
    FaceCluster {
        children: Some(ids),
        parent: None,
        first: 0,
        count: a.count + b.count,
        material: a.material,
        area: a.area + b.area,
        area_normal,
        perimeter: (a.perimeter + b.perimeter - 2.0 * shared).max(0.0),
        fit_error: quadric.fit_error(),
        cost,
        obb: Obb::around(&corners, area_normal),
        quadric,
    }
}

/// Gives each cluster its range of the triangle order (depth first from each root) and
/// returns that order.
fn number_depth_first(nodes: &mut [FaceCluster], roots: &[u32]) -> Vec<u32> {
    let leaves = nodes.iter().filter(|c| c.children.is_none()).count();
    let mut order = Vec::with_capacity(leaves);
    for &root in roots {
        let mut stack = vec![(root, false)];
        while let Some((k, done)) = stack.pop() {
            let node = &mut nodes[k as usize];
            match (node.children, done) {
                (None, _) => {
                    node.first = order.len() as u32;
                    order.push(k);
                }
                (Some([a, b]), false) => {
                    node.first = order.len() as u32;
                    stack.push((k, true));
                    stack.push((b, false));
                    stack.push((a, false));
                }
                (Some(_), true) => {}
            }
        }
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::generate::{cuboid, XorShift};

    /// Union-find over triangles joined by welded edges of one material: the surfaces.
    fn surfaces(mesh: &Mesh, materials: &[usize]) -> Vec<Vec<u32>> {
        let adjacent = dual_graph(mesh, materials);
        let mut label = vec![usize::MAX; adjacent.len()];
        let mut out = Vec::new();
        for start in 0..adjacent.len() {
            if label[start] != usize::MAX {
                continue;
            }
            let mut members = vec![];
            let mut stack = vec![start];
            label[start] = out.len();
            while let Some(t) = stack.pop() {
                members.push(t as u32);
                for &(g, _) in &adjacent[t] {
                    if label[g as usize] == usize::MAX {
                        label[g as usize] = out.len();
                        stack.push(g as usize);
                    }
                }
            }
            members.sort();
            out.push(members);
        }
        out.sort();
        out
    }

    /// Checks the structure every hierarchy must have.
    fn check(mesh: &Mesh, materials: &[usize], h: &FaceClusters) {
        let n = mesh.triangles.len();
        // Every triangle in exactly one leaf, the order a permutation.
        let mut seen = h.order.clone();
        seen.sort();
        assert_eq!(seen, (0..n as u32).collect::<Vec<_>>());
        assert_eq!(h.nodes.len(), 2 * n - h.roots.len(), "a binary forest");
        for (k, c) in h.nodes.iter().enumerate() {
            match c.children {
                None => assert_eq!(h.triangles(k as u32), &[k as u32]),
                Some([a, b]) => {
                    let joined = [h.triangles(a), h.triangles(b)].concat();
                    assert_eq!(h.triangles(k as u32), &joined[..]);
                    assert_eq!(h.nodes[a as usize].material, c.material);
                    assert_eq!(h.nodes[b as usize].material, c.material);
                }
            }
            // The box holds every corner of every triangle.
            let size = c.obb.half.length() + 1.0;
            for &t in h.triangles(k as u32) {
                for i in mesh.triangles[t as usize] {
                    assert!(c.obb.contains(mesh.positions[i as usize], 1e-9 * size));
                }
            }
        }
        // One root per connected surface of one material.
        assert_eq!(h.root_surfaces(), surfaces(mesh, materials));
        assert_eq!(
            connected_surfaces(mesh, materials),
            surfaces(mesh, materials)
        );
    }

    #[test]
    fn a_box_merges_its_faces_first() {
        let mesh = cuboid(DVec3::ZERO, DVec3::ONE);
        let materials = vec![0; mesh.triangles.len()];
        let h = FaceClusters::build(&mesh, &materials, ClusterSettings::default());
        check(&mesh, &materials, &h);
        assert_eq!(h.roots.len(), 1);
        // The first six merges are the six square faces: planar, area 1, perimeter 4.
        for c in &h.nodes[12..18] {
            assert_eq!(c.count, 2);
            assert!(c.fit_error < 1e-15, "{}", c.fit_error);
            assert!((c.area - 1.0).abs() < 1e-12 && (c.perimeter - 4.0).abs() < 1e-12);
        }
        assert!(h.nodes[18].fit_error > 0.01);
    }

    #[test]
    fn planar_input_has_zero_fit_error_at_every_level() {
        // A 20 × 20 grid of jittered points on a tilted plane, two materials in stripes.
        let mut rng = XorShift::new(5);
        let (u, v) = (DVec3::new(1.0, 0.0, 0.3), DVec3::new(0.0, 1.0, -0.2));
        let mut mesh = Mesh::default();
        for i in 0..=20 {
            for j in 0..=20 {
                let (x, y) = (
                    i as f64 + 0.3 * rng.next_f64(),
                    j as f64 + 0.3 * rng.next_f64(),
                );
                mesh.positions
                    .push(u * x + v * y + DVec3::new(5.0, -3.0, 2.0));
            }
        }
        let mut materials = Vec::new();
        for i in 0..20u32 {
            for j in 0..20u32 {
                let id = |i: u32, j: u32| i * 21 + j;
                mesh.triangles
                    .push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                mesh.triangles
                    .push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                materials.extend([(i / 7) as usize; 2]);
            }
        }
        let h = FaceClusters::build(&mesh, &materials, ClusterSettings::default());
        check(&mesh, &materials, &h);
        assert_eq!(h.roots.len(), 3, "three stripes of one material each");
        for c in &h.nodes {
            assert!(c.fit_error < 1e-12, "fit error {}", c.fit_error);
            // Flat boxes along the plane's normal.
            assert!(c.obb.half.z < 1e-9, "{:?}", c.obb);
        }
        // The whole stripe's perimeter: the outline of 7 (or 6) × 20 jittered cells.
        let total: f64 = h.roots.iter().map(|&r| h.nodes[r as usize].perimeter).sum();
        assert!(
            total > 2.0 * (3.0 * 20.0 + 20.0 * 1.04) && total < 200.0,
            "{total}"
        );
    }

    #[test]
    fn separate_and_degenerate_pieces_are_their_own_roots() {
        let mut mesh = cuboid(DVec3::ZERO, DVec3::ONE);
        let other = cuboid(DVec3::splat(3.0), DVec3::splat(4.0));
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(&other.positions);
        mesh.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
        // A zero-area triangle on its own.
        let p = mesh.positions.len() as u32;
        mesh.positions.extend([DVec3::splat(9.0); 3]);
        mesh.triangles.push([p, p + 1, p + 2]);
        let mut materials = vec![0; mesh.triangles.len()];
        materials[0] = 1; // one triangle of the first box in another material
        let h = FaceClusters::build(&mesh, &materials, ClusterSettings::default());
        check(&mesh, &materials, &h);
        assert_eq!(h.roots.len(), 4);
        assert!(h.depth() >= 4);
    }
}
