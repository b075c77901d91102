//! Who shoots in the progressive solution. Flat (`--hierarchy none`): every chart of the
//! light map — there every triangle — from its patches (blocks of 2^level texels). With
//! face clusters (Edström ch. 6, after Willmott's face-cluster radiosity): every flat
//! cluster of the hierarchy ([`RadiosityScene::planar_clusters`]), cut where a
//! cluster stops being planar, shoots as a whole — a floor drawn as 500 strips is one
//! shooter, not 500. Its shooting patches are the cells of a square grid laid in the plane
//! of its oriented box, and the grid's cell is chosen per shot by an oracle: each cell may
//! carry at most a set share of the initial unshot power (the shooter side of Hanrahan's
//! B·F refinement), so bright shooters shoot from fine cells (down to the flat solver's
//! patch) and the many weak late shooters from a few coarse ones. Receivers are always the
//! elements, so no push-pull is needed: the hierarchy only decides who shoots and from
//! where. The geometry is never changed.

use glam::{DVec2, DVec3};

use super::clusters::obb::convex_hull;
use super::clusters::{FaceClusters, Obb};
use super::polygon::{area_centroid, clip_square, outline};
use super::scene::RadiosityScene;

pub use super::Hierarchy;

/// Default largest share of the initial unshot power one shooting cell may carry.
pub const DEFAULT_CELL_POWER: f64 = 1e-3;

/// What one shooter is.
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

/// The shooters of a scene: each a set of elements with one normal and one material.
#[derive(Debug, Clone)]
pub struct Shooters {
    /// Per shooter, what it is.
    pub shapes: Vec<ShooterShape>,
    /// Per shooter, its first entry in [`Shooters::elements`].
    pub first: Vec<u32>,
    /// Per shooter, how many elements it has.
    pub count: Vec<u32>,
    /// Every shooter's elements, shooter after shooter.
    pub elements: Vec<u32>,
    /// Per shooter, its unit normal.
    pub normal: Vec<DVec3>,
    /// Per shooter, its material.
    pub material: Vec<usize>,
    /// Per shooter, its area, m².
    pub area: Vec<f64>,
    /// Per shooter, the smallest cell side it shoots from, metres (the flat patch side).
    pub finest_cell: Vec<f64>,
    /// Per element, its shooter.
    pub element_shooter: Vec<u32>,
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
}

/// How one shooter shoots: its elements in patch order, and the patches.
///
/// With several levels ([`Shooters::plan_levels`]) the patches are the cells of a quadtree
/// listed depth first (a cell, then its children's subtrees): every cell's elements are
/// one range of `order`, inside its parent's, and the top cells' ranges tile `order`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShotPlan {
    /// The shooter's elements (the same set as in [`Shooters::elements`]), patch after patch.
    pub order: Vec<u32>,
    /// The patches.
    pub patches: Vec<PlannedPatch>,
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
}

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
            let id = s.shapes.len() as u32;
            s.first.push(s.elements.len() as u32);
            s.count.push(chart.count);
            for e in chart.first..chart.first + chart.count {
                s.elements.push(e);
                s.element_shooter[e as usize] = id;
            }
            s.shapes.push(ShooterShape::Chart(c as u32));
            s.normal.push(chart.normal);
            s.material.push(chart.material);
            s.area.push(chart.area);
            s.finest_cell
                .push(chart.texel_m * f64::from(1u32 << el.level));
        }
        s
    }

    /// The flat clusters of the face-cluster hierarchy ([`RadiosityScene::planar_clusters`]):
    /// from each root, the largest clusters that are planar (within a hundredth of a texel)
    /// shoot as a whole.
    pub fn clusters(scene: &RadiosityScene) -> Shooters {
        let el = &scene.elements;
        let planar = scene.planar_clusters();
        let mut s = Shooters::empty(el.len());
        for &node in &planar.cut {
            let texel = planar.texel[node as usize];
            s.push_cluster(scene, &planar.tree, node, texel);
        }
        s
    }

    fn empty(elements: usize) -> Shooters {
        Shooters {
            shapes: Vec::new(),
            first: Vec::new(),
            count: Vec::new(),
            elements: Vec::new(),
            normal: Vec::new(),
            material: Vec::new(),
            area: Vec::new(),
            finest_cell: Vec::new(),
            element_shooter: vec![u32::MAX; elements],
        }
    }

    fn push_cluster(
        &mut self,
        scene: &RadiosityScene,
        clusters: &FaceClusters,
        node: u32,
        texel: f64,
    ) {
        let el = &scene.elements;
        let id = self.shapes.len() as u32;
        let first = self.elements.len();
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
        let mut lone_chart = None;
        for c in charts {
            let chart = &el.charts[c as usize];
            if chart.count == 0 || self.element_shooter[chart.first as usize] != u32::MAX {
                continue;
            }
            lone_chart = Some(c);
            for e in chart.first..chart.first + chart.count {
                self.elements.push(e);
                self.element_shooter[e as usize] = id;
            }
        }
        let count = self.elements.len() - first;
        if count == 0 {
            return; // only triangles without area
        }
        let c = &clusters.nodes[node as usize];
        self.first.push(first as u32);
        self.count.push(count as u32);
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
        self.shapes.push(match (c.children, lone_chart) {
            (None, Some(chart)) => ShooterShape::Chart(chart),
            _ => ShooterShape::Cluster { node, obb },
        });
        self.normal.push(obb.axes[2]);
        self.material.push(c.material);
        self.area.push(c.area);
        self.finest_cell.push(texel * f64::from(1u32 << el.level));
    }

    /// Number of shooters.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether there is no shooter.
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// Shooter `s`'s elements.
    pub fn elements_of(&self, s: usize) -> &[u32] {
        &self.elements[self.first[s] as usize..][..self.count[s] as usize]
    }

    /// The most elements any shooter has.
    pub fn max_elements(&self) -> usize {
        self.count.iter().copied().max().unwrap_or(1).max(1) as usize
    }

    /// The most cells any plan with up to `levels` coarser levels can have
    /// ([`Shooters::plan_levels`] at the finest side: coarser sides have fewer cells).
    pub fn max_cells(&self, scene: &RadiosityScene, levels: u32) -> usize {
        let el = &scene.elements;
        let cells = |s: usize| match &self.shapes[s] {
            ShooterShape::Chart(c) => el.charts[*c as usize].patch_count as usize,
            ShooterShape::Cluster { obb, .. } => {
                let grid = Grid::new(obb, self.finest_cell[s]);
                let top = levels.min(grid.levels_to_one_cell());
                let mut keys: Vec<u64> = self
                    .elements_of(s)
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
        (0..self.len()).map(cells).max().unwrap_or(1).max(1)
    }

    /// The oracle: the cell side shooter `s` shoots from when it holds `power` lm — the
    /// largest of the finest cell times a power of two whose cells (area / side² of them)
    /// carry at most `budget` lm each, stopping at one cell over the whole shooter.
    pub fn cell_side(&self, s: usize, power: f64, budget: f64) -> f64 {
        let finest = self.finest_cell[s];
        let ShooterShape::Cluster { obb, .. } = &self.shapes[s] else {
            return finest;
        };
        let whole = 2.0 * obb.half.x.max(obb.half.y);
        if !(power > 0.0 && budget > 0.0) {
            return finest;
        }
        let wanted = (self.area[s] * budget / power).sqrt();
        let mut side = finest;
        while 2.0 * side <= wanted && side < whole {
            side *= 2.0;
        }
        side
    }

    /// How shooter `s` shoots from cells of `side` metres (ignored by a triangle).
    pub fn plan(&self, scene: &RadiosityScene, s: usize, side: f64) -> ShotPlan {
        self.plan_levels(scene, s, side, 0)
    }

    /// [`Shooters::plan`] with up to `levels` coarser levels of cells above those of
    /// `side` (each doubling the side, stopping at one cell over the cluster), for
    /// [`super::links`]: far receivers take their light from a coarse cell, near ones from
    /// its children. A chart's patches have one level.
    pub fn plan_levels(
        &self,
        scene: &RadiosityScene,
        s: usize,
        side: f64,
        levels: u32,
    ) -> ShotPlan {
        match &self.shapes[s] {
            ShooterShape::Chart(c) => chart_plan(scene, *c as usize),
            ShooterShape::Cluster { obb, .. } => {
                let grid = Grid::new(obb, side);
                cluster_plan(scene, self.elements_of(s), &grid, self.normal[s], levels)
            }
        }
    }
}

/// A chart shoots from its patches (their elements are contiguous).
fn chart_plan(scene: &RadiosityScene, c: usize) -> ShotPlan {
    let el = &scene.elements;
    let chart = &el.charts[c];
    let patches = el.patches[chart.first_patch as usize..][..chart.patch_count as usize]
        .iter()
        .map(|p| PlannedPatch {
            first: p.first - chart.first,
            count: p.count,
            polygon: p.polygon.clone(),
            centroid: p.centroid,
            area: p.area,
            element_area: p.area,
            level: 0,
            parent: u32::MAX,
            radius: radius(p.centroid, &p.polygon, &[]),
        })
        .collect();
    ShotPlan {
        order: (chart.first..chart.first + chart.count).collect(),
        patches,
    }
}

/// A cluster's elements binned by centroid into square cells of the grid's side laid from
/// its box's corner, plus up to `levels` coarser levels (sides doubling; the top level has
/// at least one cell over the whole cluster or is `levels` up). Each non-empty cell is a
/// patch whose polygon is the convex hull of the cluster's triangles clipped to the cell
/// (the exact surface inside the cell wherever that is convex), in the plane through its
/// elements. A level's cells' polygons tile the surface; an element straddling two cells
/// shoots from the one holding its centroid, so a cell shoots its elements' mean
/// radiosity (power over their area) from its polygon. Elements are ordered along the
/// Z-order curve of their finest cells, so every cell's elements are one range.
fn cluster_plan(
    scene: &RadiosityScene,
    elements: &[u32],
    grid: &Grid,
    normal: DVec3,
    levels: u32,
) -> ShotPlan {
    let el = &scene.elements;
    let top = levels.min(grid.levels_to_one_cell());
    let mut keyed: Vec<(u64, u32, (u64, u64))> = elements
        .iter()
        .map(|&e| {
            let ij = grid.column_row(grid.plane(el.position[e as usize]));
            (z_order(ij), e, ij)
        })
        .collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.iter().map(|k| k.1).collect();
    let grids: Vec<Grid> = (0..=top).map(|k| grid.coarser(k)).collect();
    let pieces: Vec<_> = grids
        .iter()
        .map(|g| g.triangle_pieces(scene, &order))
        .collect();
    let mut plan = ShotPlan {
        order,
        patches: Vec::new(),
    };
    // Depth first: a cell, then its children (the next level's groups in its range).
    let mut stack: Vec<(u32, usize, usize, u32)> = groups(&keyed, 0, keyed.len(), top)
        .into_iter()
        .rev()
        .map(|(a, b)| (top, a, b, u32::MAX))
        .collect();
    while let Some((level, start, end, parent)) = stack.pop() {
        let (i, j) = keyed[start].2;
        let g = &grids[level as usize];
        let cell = (j >> level).min(g.rows - 1) * g.cols + (i >> level).min(g.cols - 1);
        let members = &plan.order[start..end];
        let outline = g.outline(
            cell,
            pieces[level as usize]
                .get(&cell)
                .map_or(&[][..], Vec::as_slice),
        );
        let here = plan.patches.len() as u32;
        plan.patches.push(cell_patch(
            scene, members, &outline, g, normal, start, level, parent,
        ));
        if level > 0 {
            for (a, b) in groups(&keyed, start, end, level - 1).into_iter().rev() {
                stack.push((level - 1, a, b, here));
            }
        }
    }
    plan
}

/// The ranges of `keyed[start..end]` that share a cell at `level` (Z-order keys agree
/// above their lowest 2 · level bits).
fn groups(
    keyed: &[(u64, u32, (u64, u64))],
    start: usize,
    end: usize,
    level: u32,
) -> Vec<(usize, usize)> {
    let shift = 2 * level;
    let mut out = Vec::new();
    let mut a = start;
    while a < end {
        let key = keyed[a].0 >> shift;
        let b = a + keyed[a..end].partition_point(|k| k.0 >> shift == key);
        out.push((a, b));
        a = b;
    }
    out
}

/// The patch of one cell: its `members` (from `order[start..]`) and its outline in the
/// grid's plane coordinates.
#[allow(clippy::too_many_arguments)]
fn cell_patch(
    scene: &RadiosityScene,
    members: &[u32],
    outline: &[DVec2],
    grid: &Grid,
    normal: DVec3,
    start: usize,
    level: u32,
    parent: u32,
) -> PlannedPatch {
    let el = &scene.elements;
    let element_area: f64 = members.iter().map(|&e| el.area[e as usize]).sum();
    let mut centroid = members
        .iter()
        .map(|&e| el.position[e as usize] * el.area[e as usize])
        .sum::<DVec3>()
        / element_area.max(1e-300);
    if level > 0 {
        // A coarse cell of a cluster that is not convex may have its centre off the
        // surface (inside a column standing on the floor): it looks from its element
        // nearest to that centre.
        centroid = members
            .iter()
            .map(|&e| el.position[e as usize])
            .min_by(|a, b| {
                a.distance_squared(centroid)
                    .total_cmp(&b.distance_squared(centroid))
            })
            .unwrap_or(centroid);
    }
    let offset = normal * centroid.dot(normal);
    let mut polygon: Vec<DVec3> = outline
        .iter()
        .map(|q| grid.u * q.x + grid.v * q.y + offset)
        .collect();
    if (polygon[1] - polygon[0])
        .cross(polygon[2] - polygon[0])
        .dot(normal)
        < 0.0
    {
        polygon.reverse();
    }
    let positions: Vec<DVec3> = members.iter().map(|&e| el.position[e as usize]).collect();
    PlannedPatch {
        first: start as u32,
        count: members.len() as u32,
        radius: radius(centroid, &polygon, &positions),
        polygon,
        centroid,
        area: area_centroid(outline).0.abs(),
        element_area,
        level,
        parent,
    }
}

/// The largest distance from `centre` to any of `polygon` and `points`.
fn radius(centre: DVec3, polygon: &[DVec3], points: &[DVec3]) -> f64 {
    polygon
        .iter()
        .chain(points)
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max)
}

/// The Z-order (Morton) key of a cell: the bits of column and row interleaved, so the
/// cells of any coarser aligned cell are one range of keys.
fn z_order((i, j): (u64, u64)) -> u64 {
    fn spread(x: u64) -> u64 {
        let mut x = x & 0xffff_ffff;
        x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        (x | (x << 1)) & 0x5555_5555_5555_5555
    }
    spread(i) | (spread(j) << 1)
}

/// A square grid in a cluster's plane: plane coordinates along `u` and `v`, cells of
/// `side` metres from `lo`, clipped to `hi`.
struct Grid {
    lo: DVec2,
    hi: DVec2,
    side: f64,
    cols: u64,
    rows: u64,
    u: DVec3,
    v: DVec3,
}

impl Grid {
    /// Cells of `side` metres over the plane of `obb` (axes 0 and 1).
    fn new(obb: &Obb, side: f64) -> Grid {
        let [u, v, _] = obb.axes;
        let lo = DVec2::new(
            obb.centre.dot(u) - obb.half.x,
            obb.centre.dot(v) - obb.half.y,
        );
        let hi = lo + 2.0 * DVec2::new(obb.half.x, obb.half.y);
        Grid::with_side(lo, hi, side, u, v)
    }

    fn with_side(lo: DVec2, hi: DVec2, side: f64, u: DVec3, v: DVec3) -> Grid {
        Grid {
            lo,
            hi,
            side,
            cols: (((hi.x - lo.x) / side).ceil() as u64).max(1),
            rows: (((hi.y - lo.y) / side).ceil() as u64).max(1),
            u,
            v,
        }
    }

    /// The grid `level` levels up: cells 2^level times the side, from the same corner, so
    /// cell (i, j) holds the fine cells (i ≫ level, j ≫ level) maps to it.
    fn coarser(&self, level: u32) -> Grid {
        let side = self.side * f64::from(1u32 << level);
        Grid::with_side(self.lo, self.hi, side, self.u, self.v)
    }

    /// How many levels up one cell covers the grid.
    fn levels_to_one_cell(&self) -> u32 {
        let mut level = 0;
        while (self.cols.max(self.rows) - 1) >> level > 0 {
            level += 1;
        }
        level
    }

    fn plane(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.u), p.dot(self.v))
    }

    /// Column and row of the cell holding `q` (clamped to the grid).
    fn column_row(&self, q: DVec2) -> (u64, u64) {
        let q = (q - self.lo) / self.side;
        let i = (q.x.max(0.0) as u64).min(self.cols - 1);
        let j = (q.y.max(0.0) as u64).min(self.rows - 1);
        (i, j)
    }

    fn bounds(&self, cell: u64) -> (DVec2, DVec2) {
        let (i, j) = (cell % self.cols, cell / self.cols);
        let lo = self.lo + DVec2::new(i as f64, j as f64) * self.side;
        (lo, (lo + DVec2::splat(self.side)).min(self.hi))
    }

    /// Per cell, the corners of the pieces of the elements' triangles inside it.
    fn triangle_pieces(
        &self,
        scene: &RadiosityScene,
        elements: &[u32],
    ) -> std::collections::HashMap<u64, Vec<DVec2>> {
        let mesh = &scene.casters;
        let el = &scene.elements;
        let mut charts: Vec<u32> = elements.iter().map(|&e| el.chart[e as usize]).collect();
        charts.sort_unstable();
        charts.dedup();
        let triangles = charts
            .iter()
            .flat_map(|&c| el.charts[c as usize].triangles.iter().copied());
        let mut pieces: std::collections::HashMap<u64, Vec<DVec2>> = Default::default();
        for t in triangles {
            let mut c = mesh.triangles[t as usize].map(|i| self.plane(mesh.positions[i as usize]));
            if (c[1] - c[0]).perp_dot(c[2] - c[0]) < 0.0 {
                c.swap(1, 2);
            }
            let (i0, j0) = self.column_row(c[0].min(c[1]).min(c[2]));
            let (i1, j1) = self.column_row(c[0].max(c[1]).max(c[2]));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let cell = j * self.cols + i;
                    let (lo, hi) = self.bounds(cell);
                    let piece = clip_square(lo, hi, &c);
                    if piece.len() >= 3 {
                        pieces.entry(cell).or_default().extend(piece);
                    }
                }
            }
        }
        pieces
    }

    /// The convex hull of a cell's triangle pieces: at most 8 corners (the shot record's
    /// limit; more become the hull's bounding rectangle), at least a triangle (the cell
    /// when the pieces have no area).
    fn outline(&self, cell: u64, pieces: &[DVec2]) -> Vec<DVec2> {
        let (lo, hi) = self.bounds(cell);
        outline(&convex_hull(pieces), lo, hi)
    }
}
