//! Adaptive subdivision (Wallner §2.4): a chart's texel grid is laid at the finest
//! resolution, and its elements are square blocks of 2^levels texels wherever nothing
//! calls for more; a block that a [`SplitTest`] finds on a shadow boundary is split into
//! four, recursively, down to single texels. The light map keeps the fine texels (a block
//! shows its value on all of its texels), so subdivision happens inside the atlas, and the
//! solver's cost follows the elements, not the texels.

use glam::{DVec2, DVec3};

use super::plan::{ChartPlan, Laid};

/// How far elements may be subdivided, and when.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Subdivision {
    /// Elements are 2^`levels` texels square where no shadow boundary crosses them, and
    /// split down to single texels where one does; 0 lays every texel as an element
    /// (uniform elements).
    pub levels: u32,
    /// Wallner's b_l: a block is split when the share of its sample points that a light
    /// reaches lies within `lower..=upper` (and is neither none nor all of them).
    pub lower: f64,
    /// Wallner's b_u (see [`Self::lower`]).
    pub upper: f64,
}

impl Default for Subdivision {
    fn default() -> Subdivision {
        Subdivision::NONE
    }
}

impl Subdivision {
    /// Uniform elements: one per texel.
    pub const NONE: Subdivision = Subdivision {
        levels: 0,
        lower: 0.0,
        upper: 1.0,
    };

    /// Elements of 2^`levels` texels split at every shadow boundary (any share).
    pub fn levels(levels: u32) -> Subdivision {
        Subdivision {
            levels,
            ..Subdivision::NONE
        }
    }

    /// The side of an unsplit element, texels (saturating: levels beyond
    /// [`super::MAX_SUBDIVISION`] are refused when elements are built).
    pub fn block(&self) -> u32 {
        1u32.checked_shl(self.levels).unwrap_or(u32::MAX)
    }

    /// Whether `reached` of `facing` sample points being lit calls for a split: some but
    /// not all, in a share within the bounds.
    pub fn partial(&self, reached: usize, facing: usize) -> bool {
        if reached == 0 || reached >= facing {
            return false;
        }
        let share = reached as f64 / facing as f64;
        (self.lower..=self.upper).contains(&share)
    }
}

/// Decides whether a block of texels is split into four.
pub trait SplitTest: Sync {
    /// Whether the block whose finest elements have their centroids at `points` (on a
    /// chart facing `normal`) straddles a boundary.
    fn split(&self, points: &[DVec3], normal: DVec3) -> bool;
}

/// Never splits (uniform elements).
pub struct NeverSplit;

impl SplitTest for NeverSplit {
    fn split(&self, _: &[DVec3], _: DVec3) -> bool {
        false
    }
}

/// One element before packing: its block of texels (column, row of its lower-left
/// texel, side) and the area (m²) and centroid (plane coordinates) of what it covers.
#[derive(Debug, Clone, Copy)]
pub(super) struct Block {
    pub(super) column: u32,
    pub(super) row: u32,
    pub(super) side: u32,
    pub(super) area: f64,
    pub(super) centroid: DVec2,
}

/// One shooting patch before packing: its place in the grid of patches and its elements.
pub(super) struct LaidPatch {
    pub(super) key: (u32, u32),
    pub(super) elements: Vec<Block>,
}

/// The elements of `plan`, patch by patch (patches of `patch` texels, in row-major
/// order), each patch's elements blocks of `coarse` texels split where `test` says.
pub(super) fn lay_out(
    plan: &ChartPlan,
    patch: u32,
    coarse: u32,
    test: &dyn SplitTest,
) -> Vec<LaidPatch> {
    let laid = plan.elements();
    if coarse == 1 {
        return one_texel_each(&laid, patch);
    }
    let mut grid = vec![u32::MAX; plan.cols as usize * plan.rows as usize];
    for (k, &(i, j, ..)) in laid.iter().enumerate() {
        grid[j as usize * plan.cols as usize + i as usize] = k as u32;
    }
    let mut keys: Vec<(u32, u32)> = laid.iter().map(|e| (e.1 / patch, e.0 / patch)).collect();
    keys.sort_unstable();
    keys.dedup();
    let splitter = Splitter {
        plan,
        laid: &laid,
        grid: &grid,
        test,
    };
    keys.into_iter()
        .map(|(pj, pi)| {
            let mut elements = Vec::new();
            let per_side = patch / coarse;
            for bj in 0..per_side {
                for bi in 0..per_side {
                    let (column, row) = (pi * patch + bi * coarse, pj * patch + bj * coarse);
                    splitter.block(column, row, coarse, &mut elements);
                }
            }
            LaidPatch {
                key: (pi, pj),
                elements,
            }
        })
        .collect()
}

/// Uniform elements, one per texel, patch by patch (no grid of the chart's texels).
fn one_texel_each(laid: &[Laid], patch: u32) -> Vec<LaidPatch> {
    let mut order: Vec<&Laid> = laid.iter().collect();
    order.sort_by_key(|e| (e.1 / patch, e.0 / patch, e.1, e.0));
    let mut out: Vec<LaidPatch> = Vec::new();
    for &(column, row, area, centroid) in order {
        let key = (column / patch, row / patch);
        if out.last().is_none_or(|p| p.key != key) {
            out.push(LaidPatch {
                key,
                elements: Vec::new(),
            });
        }
        if let Some(p) = out.last_mut() {
            p.elements.push(Block {
                column,
                row,
                side: 1,
                area,
                centroid,
            });
        }
    }
    out
}

struct Splitter<'a> {
    plan: &'a ChartPlan,
    laid: &'a [Laid],
    grid: &'a [u32],
    test: &'a dyn SplitTest,
}

impl Splitter<'_> {
    /// The finest elements in the block of `side` texels at (`column`, `row`).
    fn members(&self, column: u32, row: u32, side: u32) -> Vec<&Laid> {
        let (cols, rows) = (self.plan.cols, self.plan.rows);
        (row..(row + side).min(rows))
            .flat_map(|j| (column..(column + side).min(cols)).map(move |i| (i, j)))
            .filter_map(|(i, j)| {
                let k = self.grid[j as usize * cols as usize + i as usize];
                (k != u32::MAX).then(|| &self.laid[k as usize])
            })
            .collect()
    }

    /// Pushes the block's elements: itself, or its four quarters' when it is split.
    fn block(&self, column: u32, row: u32, side: u32, out: &mut Vec<Block>) {
        let members = self.members(column, row, side);
        if members.is_empty() {
            return;
        }
        if side > 1 {
            let points: Vec<DVec3> = members.iter().map(|e| self.plan.to_world(e.3)).collect();
            if self.test.split(&points, self.plan.normal) {
                let half = side / 2;
                for (dj, di) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    self.block(column + di * half, row + dj * half, half, out);
                }
                return;
            }
        }
        let area: f64 = members.iter().map(|e| e.2).sum();
        let moment: DVec2 = members.iter().map(|e| e.3 * e.2).sum();
        out.push(Block {
            column,
            row,
            side,
            area,
            centroid: moment / area,
        });
    }
}
