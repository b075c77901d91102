//! Who shoots in the progressive solution. Flat (`--hierarchy none`): every chart of the
//! light map — there every triangle — from its patches (blocks of 2^level texels). With
//! face clusters (Edström ch. 4 and 6, after Willmott's face-cluster radiosity): every
//! connected surface of one material (a root of the hierarchy) is one shooter, chosen by
//! its summed unshot power, and its **pieces** are its flat clusters
//! ([`RadiosityScene::planar_clusters`], cut where a cluster stops being planar) — a floor
//! drawn as 500 strips is one piece, a column of 60 facets one shooter, not 60.
//!
//! Per shot ([`Shooters::plan_shot`]), with each piece's unshot power summed on the GPU:
//! - a piece shoots from the cells of a square grid laid in the plane of its oriented box,
//!   the cell chosen by an oracle: each cell may carry at most a set share of the initial
//!   unshot power (the shooter side of Hanrahan's B·F refinement), so bright pieces shoot
//!   from fine cells (down to the flat solver's patch) and weak ones from a few coarse ones;
//! - the largest face clusters of two pieces or more that together carry at most that
//!   share and whose normals agree (|ΣA·n| ≥ [`MERGE_NORMALS`] ΣA) shoot from one merged
//!   cell facing their summed area normal — Willmott's power vector S·b for a curved
//!   cluster, its error bounded by the cell's power times the normals' spread;
//! - pieces (or merged cells) with less than [`SKIP_SHARE`] of the strongest one's power
//!   wait for a later shot.
//!
//! Receivers are always the elements (a shooter's pieces light each other, a cell never
//! its own pieces), so no push-pull is needed: the hierarchy only decides who shoots and
//! from where. The geometry is never changed.

mod cache;
mod cells;

pub use cache::{PlanCache, UnitKey, DEFAULT_PLAN_CACHE_BYTES};
use glam::{DVec2, DVec3};

use super::clusters::obb::convex_hull;
use super::clusters::{FaceClusters, Obb};
use super::polygon::{frame, outline};
use super::scene::RadiosityScene;
use cells::{cell_patch, chart_plan, cluster_plan, nearest_member, z_order, Grid, PieceFrame};

pub use super::Hierarchy;

/// Default largest share of the initial unshot power one shooting cell may carry.
pub const DEFAULT_CELL_POWER: f64 = 1e-3;

/// What one planar piece of a shooter is.
#[derive(Debug, Clone, PartialEq)]
pub enum ShooterShape {
    /// One chart (a triangle, or a planar cluster's triangles), shot from its patches.
    Chart(u32),
    /// A flat face cluster, shot from grid cells in the plane of its box.
    Cluster {
        /// The cluster's node in the hierarchy.
        node: u32,
        /// Its box: axes 0 and 1 span the plane, axis 2 is the normal.
        obb: Obb,
    },
}

/// One planar piece of a shooter: its elements share a plane, a normal and a grid of
/// cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// What it is.
    pub shape: ShooterShape,
    /// Its unit normal.
    pub normal: DVec3,
    /// Its area, m².
    pub area: f64,
    /// The smallest cell side it shoots from, metres (the flat patch side).
    pub finest_cell: f64,
    /// Its elements are `elements[first..first + count]` of [`Shooters`].
    pub first: u32,
    /// How many elements it has.
    pub count: u32,
    /// Its node in the face-cluster hierarchy (`u32::MAX` for a chart of the flat solver).
    pub node: u32,
}

/// The shooters of a scene: each a set of planar pieces of one material, chosen and shot
/// as a whole.
#[derive(Debug, Clone)]
pub struct Shooters {
    /// Every shooter's pieces, shooter after shooter.
    pub pieces: Vec<Piece>,
    /// Per shooter, its first piece.
    pub first_piece: Vec<u32>,
    /// Per shooter, how many pieces it has.
    pub piece_count: Vec<u32>,
    /// Per shooter, the face cluster holding its pieces (`u32::MAX` for a lone piece).
    pub node: Vec<u32>,
    /// Per shooter, its first entry in [`Shooters::elements`].
    pub first: Vec<u32>,
    /// Per shooter, how many elements it has.
    pub count: Vec<u32>,
    /// Every piece's elements, piece after piece.
    pub elements: Vec<u32>,
    /// Per shooter, its material.
    pub material: Vec<usize>,
    /// Per shooter, its area, m².
    pub area: Vec<f64>,
    /// Per element, its shooter.
    pub element_shooter: Vec<u32>,
    /// Per element, its piece.
    pub element_piece: Vec<u32>,
}

/// One shooting patch of a shot: a range of the shot's element order and a polygon.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedPatch {
    /// First entry of [`ShotPlan::order`].
    pub first: u32,
    /// Number of elements.
    pub count: u32,
    /// Convex polygon counter-clockwise seen from the front, metres.
    pub polygon: Vec<DVec3>,
    /// Where it looks from: the area-weighted centre of its elements, metres.
    pub centroid: DVec3,
    /// The direction it faces (its visibility map's axis and its polygon's normal).
    pub normal: DVec3,
    /// The polygon's area, m².
    pub area: f64,
    /// Its elements' area, m²: it shoots their power over this, their mean radiosity.
    pub element_area: f64,
    /// Its level in the cell quadtree: 0 the finest cells, each level up doubles the side.
    pub level: u32,
    /// The cell one level up that holds it, an index into [`ShotPlan::patches`];
    /// `u32::MAX` for a top cell.
    pub parent: u32,
    /// The largest distance from `centroid` to its polygon's corners or its elements'
    /// centres, metres.
    pub radius: f64,
    /// The pieces whose elements it shoots (first, end), indices into [`Shooters::pieces`]:
    /// they do not receive its light.
    pub pieces: [u32; 2],
    /// Whether it is a merged cell: several planar pieces of a weak shooter shot as one
    /// cell facing their summed area normal, its polygon their outline projected on that
    /// plane.
    pub merged: bool,
}

impl PlannedPatch {
    /// What its polygon's radiosity is scaled by so that it shoots its elements' power:
    /// their area over its polygon's where the polygon stands in for them (a coarse cell's
    /// outline, a merged cell's projection), else 1 (a fine cell's polygon is the surface
    /// it holds).
    pub fn power_scale(&self) -> f64 {
        if (self.level > 0 || self.merged) && self.area > 0.0 {
            self.element_area / self.area
        } else {
            1.0
        }
    }
}

/// How one shooter shoots: its elements in patch order, and the patches.
///
/// With several levels ([`Shooters::plan_levels`]) each piece's patches are the cells of a
/// quadtree listed depth first (a cell, then its children's subtrees): every cell's
/// elements are one range of `order`, inside its parent's, and the top cells' ranges
/// tile `order[..shot]`. The elements after `shot` are not shot this time (pieces too
/// weak to be worth a visibility map yet: [`SKIP_SHARE`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShotPlan {
    /// The shooter's elements (the same set as in [`Shooters::elements`]), patch after patch.
    pub order: Vec<u32>,
    /// The patches.
    pub patches: Vec<PlannedPatch>,
    /// How many entries of `order` are shot.
    pub shot: u32,
}

impl ShotPlan {
    /// The children of each patch (indices into [`ShotPlan::patches`]).
    pub fn children(&self) -> Vec<Vec<u32>> {
        let mut children = vec![Vec::new(); self.patches.len()];
        for (k, p) in self.patches.iter().enumerate() {
            if p.parent != u32::MAX {
                children[p.parent as usize].push(k as u32);
            }
        }
        children
    }

    /// The planes its cells shoot from ([`cell_planes`]).
    pub fn planes(&self) -> Vec<(DVec3, DVec3, f64)> {
        cell_planes(&self.patches)
    }

    /// Appends `plan` (shot in full) after the shot part of this one.
    fn append(&mut self, plan: ShotPlan) {
        let (order, patches) = (self.order.len() as u32, self.patches.len() as u32);
        self.order.extend(plan.order);
        self.patches.extend(plan.patches.into_iter().map(|mut p| {
            p.first += order;
            if p.parent != u32::MAX {
                p.parent += patches;
            }
            p
        }));
        self.shot = self.order.len() as u32;
    }
}

/// The planes `patches` shoot from (unit normal, a point, how thick the cells' centres are
/// about it, metres): one per run of consecutive cells facing one way.
pub fn cell_planes(patches: &[PlannedPatch]) -> Vec<(DVec3, DVec3, f64)> {
    let mut planes: Vec<(DVec3, DVec3, f64)> = Vec::new();
    for p in patches {
        match planes.last_mut() {
            Some((n, at, thickness)) if *n == p.normal => {
                *thickness = thickness.max(n.dot(p.centroid - *at).abs());
            }
            _ => planes.push((p.normal, p.centroid, 0.0)),
        }
    }
    planes
}

/// A shooter's pieces that shoot from one merged cell must agree in normal: their summed
/// area normal is at least this share of their area (its deviation is the error bound of
/// the merge, with the cell's power at most the oracle's budget).
pub const MERGE_NORMALS: f64 = 0.8;
/// In a shot, pieces (or merged cells) with less than this share of the strongest one's
/// unshot power wait for a later shot.
pub const SKIP_SHARE: f64 = 0.05;

impl Shooters {
    /// The shooters `hierarchy` asks for.
    pub fn build(scene: &RadiosityScene, hierarchy: Hierarchy) -> Shooters {
        match hierarchy {
            Hierarchy::None => Shooters::flat(scene),
            Hierarchy::Clusters => Shooters::clusters(scene),
        }
    }

    /// Every chart with elements is a shooter (with per-triangle charts: every triangle).
    pub fn flat(scene: &RadiosityScene) -> Shooters {
        let el = &scene.elements;
        let mut s = Shooters::empty(el.len());
        for (c, chart) in el.charts.iter().enumerate() {
            if chart.count == 0 {
                continue;
            }
            let start = s.start();
            s.push_piece(
                chart.first..chart.first + chart.count,
                Piece {
                    shape: ShooterShape::Chart(c as u32),
                    normal: chart.normal,
                    area: chart.area,
                    finest_cell: chart.texel_m * f64::from(1u32 << el.level),
                    first: 0,
                    count: 0,
                    node: u32::MAX,
                },
            );
            s.finish(start, u32::MAX, chart.material);
        }
        s
    }

    /// Each connected surface of one material (a root of the face-cluster hierarchy) is
    /// one shooter whose pieces are its flat clusters ([`RadiosityScene::planar_clusters`]:
    /// from each root, the largest clusters that are planar within a hundredth of a texel).
    /// Its pieces shoot from their own cells, sized by their own unshot power, and a weak
    /// surface's curved parts from merged cells ([`Shooters::plan_shot`]).
    pub fn clusters(scene: &RadiosityScene) -> Shooters {
        Shooters::from_clusters(scene, true)
    }

    /// Every flat cluster its own shooter: the pieces of [`Shooters::clusters`], each
    /// chosen on its own (a reference for the grouping).
    pub fn planar(scene: &RadiosityScene) -> Shooters {
        Shooters::from_clusters(scene, false)
    }

    fn from_clusters(scene: &RadiosityScene, by_surface: bool) -> Shooters {
        let el = &scene.elements;
        let planar = scene.planar_clusters();
        let tree = &planar.tree;
        let mut s = Shooters::empty(el.len());
        // The cut in depth-first order, so every cluster's pieces are consecutive.
        let mut cut = planar.cut.clone();
        cut.sort_unstable_by_key(|&n| tree.nodes[n as usize].first);
        let mut roots = tree.roots.clone();
        roots.sort_unstable_by_key(|&n| tree.nodes[n as usize].first);
        let mut next = 0;
        for &root in &roots {
            let r = &tree.nodes[root as usize];
            let from = next;
            while next < cut.len() && tree.nodes[cut[next] as usize].first < r.first + r.count {
                next += 1;
            }
            let groups: Vec<(u32, &[u32])> = if by_surface {
                vec![(root, &cut[from..next])]
            } else {
                (from..next).map(|k| (cut[k], &cut[k..k + 1])).collect()
            };
            for (node, pieces) in groups {
                let start = s.start();
                for &piece in pieces {
                    s.push_cluster(scene, tree, piece, planar.texel[piece as usize]);
                }
                s.finish(start, node, r.material);
            }
        }
        s
    }

    fn empty(elements: usize) -> Shooters {
        Shooters {
            pieces: Vec::new(),
            first_piece: Vec::new(),
            piece_count: Vec::new(),
            node: Vec::new(),
            first: Vec::new(),
            count: Vec::new(),
            elements: Vec::new(),
            material: Vec::new(),
            area: Vec::new(),
            element_shooter: vec![u32::MAX; elements],
            element_piece: vec![u32::MAX; elements],
        }
    }

    /// Where the next shooter's pieces and elements start.
    fn start(&self) -> (usize, usize) {
        (self.pieces.len(), self.elements.len())
    }

    /// Adds `piece` with `elements` to the shooter being built.
    fn push_piece(&mut self, elements: impl IntoIterator<Item = u32>, mut piece: Piece) {
        let (id, index) = (self.first.len() as u32, self.pieces.len() as u32);
        piece.first = self.elements.len() as u32;
        for e in elements {
            self.elements.push(e);
            self.element_shooter[e as usize] = id;
            self.element_piece[e as usize] = index;
        }
        piece.count = self.elements.len() as u32 - piece.first;
        self.pieces.push(piece);
    }

    /// Closes the shooter whose pieces were pushed since `start` (dropped when it has
    /// none: only triangles without area).
    fn finish(&mut self, (pieces, elements): (usize, usize), node: u32, material: usize) {
        if self.pieces.len() == pieces {
            return;
        }
        self.first_piece.push(pieces as u32);
        self.piece_count.push((self.pieces.len() - pieces) as u32);
        self.node.push(node);
        self.first.push(elements as u32);
        self.count.push((self.elements.len() - elements) as u32);
        self.material.push(material);
        self.area
            .push(self.pieces[pieces..].iter().map(|p| p.area).sum());
    }

    fn push_cluster(
        &mut self,
        scene: &RadiosityScene,
        clusters: &FaceClusters,
        node: u32,
        texel: f64,
    ) {
        let el = &scene.elements;
        // Its triangles' charts' elements (a chart is never split between clusters when
        // the charts are the planar clusters; otherwise the first cluster claims it).
        let mut charts: Vec<u32> = clusters
            .triangles(node)
            .iter()
            .map(|&t| el.triangles[t as usize].chart)
            .filter(|&c| c != u32::MAX)
            .collect();
        charts.sort_unstable();
        charts.dedup();
        let mut elements = Vec::new();
        let mut lone_chart = None;
        for c in charts {
            let chart = &el.charts[c as usize];
            if chart.count == 0 || self.element_shooter[chart.first as usize] != u32::MAX {
                continue;
            }
            lone_chart = Some(c);
            elements.extend(chart.first..chart.first + chart.count);
        }
        if elements.is_empty() {
            return; // only triangles without area
        }
        let c = &clusters.nodes[node as usize];
        // A lone triangle shoots from its own patches, which follow its outline. A
        // cluster's cells are laid in the tight box around its corners (the hierarchy's
        // boxes, around the children's boxes, are looser: cells must not stick out).
        let mesh = &scene.casters;
        let corners: Vec<DVec3> = clusters
            .triangles(node)
            .iter()
            .flat_map(|&t| mesh.triangles[t as usize].map(|i| mesh.positions[i as usize]))
            .collect();
        let obb = Obb::around(&corners, c.area_normal);
        let shape = match (c.children, lone_chart) {
            (None, Some(chart)) => ShooterShape::Chart(chart),
            _ => ShooterShape::Cluster { node, obb },
        };
        self.push_piece(
            elements,
            Piece {
                shape,
                normal: obb.axes[2],
                area: c.area,
                finest_cell: texel * f64::from(1u32 << el.level),
                first: 0,
                count: 0,
                node,
            },
        );
    }

    /// Number of shooters.
    pub fn len(&self) -> usize {
        self.first.len()
    }

    /// Whether there is no shooter.
    pub fn is_empty(&self) -> bool {
        self.first.is_empty()
    }

    /// Shooter `s`'s elements.
    pub fn elements_of(&self, s: usize) -> &[u32] {
        &self.elements[self.first[s] as usize..][..self.count[s] as usize]
    }

    /// Shooter `s`'s pieces' indices.
    pub fn pieces_of(&self, s: usize) -> std::ops::Range<usize> {
        let first = self.first_piece[s] as usize;
        first..first + self.piece_count[s] as usize
    }

    /// Piece `p`'s elements.
    pub fn piece_elements(&self, p: usize) -> &[u32] {
        let piece = &self.pieces[p];
        &self.elements[piece.first as usize..][..piece.count as usize]
    }

    /// The most elements any shooter has.
    pub fn max_elements(&self) -> usize {
        self.count.iter().copied().max().unwrap_or(1).max(1) as usize
    }

    /// The most cells any plan with up to `levels` coarser levels can have (every piece
    /// at its finest side: coarser sides and merged cells have fewer).
    pub fn max_cells(&self, scene: &RadiosityScene, levels: u32) -> usize {
        let el = &scene.elements;
        let cells = |p: usize| match &self.pieces[p].shape {
            ShooterShape::Chart(c) => el.charts[*c as usize].patch_count as usize,
            ShooterShape::Cluster { obb, .. } => {
                let grid = Grid::new(obb, self.pieces[p].finest_cell);
                let top = levels.min(grid.levels_to_one_cell());
                let mut keys: Vec<u64> = self
                    .piece_elements(p)
                    .iter()
                    .map(|&e| z_order(grid.column_row(grid.plane(el.position[e as usize]))))
                    .collect();
                keys.sort_unstable();
                (0..=top)
                    .map(|k| {
                        let mut level: Vec<u64> = keys.iter().map(|m| m >> (2 * k)).collect();
                        level.dedup();
                        level.len()
                    })
                    .sum()
            }
        };
        (0..self.len())
            .map(|s| self.pieces_of(s).map(cells).sum::<usize>())
            .max()
            .unwrap_or(1)
            .max(1)
    }

    /// The oracle: the cell side piece `p` shoots from when it holds `power` lm — the
    /// largest of the finest cell times a power of two whose cells (area / side² of them)
    /// carry at most `budget` lm each, stopping at one cell over the whole piece.
    pub fn cell_side(&self, p: usize, power: f64, budget: f64) -> f64 {
        let piece = &self.pieces[p];
        let finest = piece.finest_cell;
        let ShooterShape::Cluster { obb, .. } = &piece.shape else {
            return finest;
        };
        let whole = 2.0 * obb.half.x.max(obb.half.y);
        if !(power > 0.0 && budget > 0.0) {
            return finest;
        }
        let wanted = (piece.area * budget / power).sqrt();
        let mut side = finest;
        while 2.0 * side <= wanted && side < whole {
            side *= 2.0;
        }
        side
    }

    /// How shooter `s` shoots with every piece from cells of `side` metres (or its finest
    /// cell where that is larger; a chart from its patches), one level.
    pub fn plan(&self, scene: &RadiosityScene, s: usize, side: f64) -> ShotPlan {
        self.plan_levels(scene, s, side, 0)
    }

    /// [`Shooters::plan`] with up to `levels` coarser levels of cells above those of
    /// `side` in each piece (each doubling the side, stopping at one cell over the piece),
    /// for [`super::links`]: far receivers take their light from a coarse cell, near ones
    /// from its children. A chart's patches have one level.
    pub fn plan_levels(
        &self,
        scene: &RadiosityScene,
        s: usize,
        side: f64,
        levels: u32,
    ) -> ShotPlan {
        let mut plan = ShotPlan::default();
        for p in self.pieces_of(s) {
            let side = side.max(self.pieces[p].finest_cell);
            plan.append(self.piece_plan(scene, p, side, levels));
        }
        plan
    }

    /// How shooter `s` shoots when its pieces hold `power` lm each (unshot, per piece of
    /// [`Shooters::pieces_of`]) and a cell may carry `budget` lm: each piece from cells
    /// sized by the oracle for its own power ([`Shooters::cell_side`]) with up to `levels`
    /// coarser levels; the largest clusters of two or more pieces that together carry at
    /// most `budget` and agree in normal ([`MERGE_NORMALS`]) from one merged cell; and the
    /// pieces or merged cells with less than [`SKIP_SHARE`] of the strongest one's power
    /// not at all this time (they stay unshot, after [`ShotPlan::shot`]). The units'
    /// plans come from `cache` where it holds them, and the ones made are kept there (the
    /// same plan either way; `PlanCache::new(0)` keeps none).
    pub fn plan_shot(
        &self,
        scene: &RadiosityScene,
        s: usize,
        power: &[f64],
        budget: f64,
        levels: u32,
        cache: &mut PlanCache,
    ) -> ShotPlan {
        let pieces = self.pieces_of(s);
        debug_assert_eq!(power.len(), pieces.len());
        let units = self.units(scene, s, power, budget);
        let strongest = units.iter().map(|u| u.1).fold(0.0, f64::max);
        let mut plan = ShotPlan::default();
        let mut waiting = Vec::new();
        for (range, unit_power, merged) in units {
            if unit_power < SKIP_SHARE * strongest {
                waiting.extend(range.flat_map(|p| self.piece_elements(p).iter().copied()));
            } else if let Some(node) = merged {
                let key = UnitKey::Merged {
                    first: range.start as u32,
                    end: range.end as u32,
                    node,
                };
                plan.append(cache.get_or_make(key, || self.merged_plan(scene, range, node)));
            } else {
                let p = range.start;
                let side = self.cell_side(p, unit_power, budget);
                let key = UnitKey::Piece {
                    piece: p as u32,
                    side_bits: side.max(self.pieces[p].finest_cell).to_bits(),
                    levels,
                };
                plan.append(cache.get_or_make(key, || self.piece_plan(scene, p, side, levels)));
            }
        }
        plan.order.extend(waiting);
        plan
    }

    /// Shooter `s`'s shooting units in piece order: (pieces, unshot power, the face
    /// cluster of a merged cell).
    fn units(
        &self,
        scene: &RadiosityScene,
        s: usize,
        power: &[f64],
        budget: f64,
    ) -> Vec<(std::ops::Range<usize>, f64, Option<u32>)> {
        let pieces = self.pieces_of(s);
        let lone = |k: usize| (pieces.start + k..pieces.start + k + 1, power[k], None);
        let root = self.node[s];
        if pieces.len() < 2 || root == u32::MAX || budget.is_nan() || budget <= 0.0 {
            return (0..pieces.len()).map(lone).collect();
        }
        let tree = &scene.planar_clusters().tree;
        // The pieces in depth-first order: a cluster's pieces are those whose nodes start
        // in its range of the hierarchy's order.
        let starts: Vec<u32> = pieces
            .clone()
            .map(|p| tree.nodes[self.pieces[p].node as usize].first)
            .collect();
        let mut sum = vec![0.0];
        for &w in power {
            sum.push(sum.last().copied().unwrap_or(0.0) + w);
        }
        let mut units = Vec::new();
        let mut stack = vec![root];
        while let Some(node) = stack.pop() {
            let c = &tree.nodes[node as usize];
            let a = starts.partition_point(|&f| f < c.first);
            let b = starts.partition_point(|&f| f < c.first + c.count);
            if b <= a {
                continue;
            }
            let held = sum[b] - sum[a];
            let piece =
                starts[a] == c.first && b == a + 1 && self.pieces[pieces.start + a].node == node;
            if piece {
                units.push(lone(a));
            } else if b - a >= 2
                && held <= budget
                && c.area_normal.length() >= MERGE_NORMALS * c.area
            {
                units.push((pieces.start + a..pieces.start + b, held, Some(node)));
            } else if let Some([l, r]) = c.children {
                // Depth first, in the order's order.
                let (l, r) = if tree.nodes[l as usize].first < tree.nodes[r as usize].first {
                    (l, r)
                } else {
                    (r, l)
                };
                stack.push(r);
                stack.push(l);
            }
        }
        units
    }

    /// Piece `p` from cells of `side` metres with up to `levels` coarser levels.
    fn piece_plan(&self, scene: &RadiosityScene, p: usize, side: f64, levels: u32) -> ShotPlan {
        let piece = &self.pieces[p];
        let range = [p as u32, p as u32 + 1];
        match &piece.shape {
            ShooterShape::Chart(c) => chart_plan(scene, *c as usize, range),
            ShooterShape::Cluster { obb, .. } => {
                let grid = Grid::new(obb, side);
                let at = PieceFrame {
                    normal: piece.normal,
                    pieces: range,
                };
                cluster_plan(scene, self.piece_elements(p), &grid, &at, levels)
            }
        }
    }

    /// The pieces `range` (under face cluster `node`) as one cell facing their summed
    /// area normal, looking from their element nearest their centre, its polygon the
    /// outline of their corners projected on its plane.
    fn merged_plan(
        &self,
        scene: &RadiosityScene,
        range: std::ops::Range<usize>,
        node: u32,
    ) -> ShotPlan {
        let tree = &scene.planar_clusters().tree;
        let normal = tree.nodes[node as usize].area_normal.normalize();
        let (u, v) = frame(normal);
        let order: Vec<u32> = range
            .clone()
            .flat_map(|p| self.piece_elements(p).iter().copied())
            .collect();
        let mesh = &scene.casters;
        let projected: Vec<DVec2> = tree
            .triangles(node)
            .iter()
            .flat_map(|&t| mesh.triangles[t as usize])
            .map(|i| {
                let q = mesh.positions[i as usize];
                DVec2::new(q.dot(u), q.dot(v))
            })
            .collect();
        let hull = convex_hull(&projected);
        let lo = hull.iter().copied().fold(DVec2::INFINITY, DVec2::min);
        let hi = hull.iter().copied().fold(DVec2::NEG_INFINITY, DVec2::max);
        let at = PieceFrame {
            normal,
            pieces: [range.start as u32, range.end as u32],
        };
        let mut patch = cell_patch(
            scene,
            &order,
            &outline(&hull, lo, hi),
            (u, v),
            &at,
            0,
            0,
            u32::MAX,
        );
        patch.merged = true;
        patch.centroid = nearest_member(scene, &order, patch.centroid);
        ShotPlan {
            shot: order.len() as u32,
            order,
            patches: vec![patch],
        }
    }
}
