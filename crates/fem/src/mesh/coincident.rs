//! Coincident nodes: a spatial index to find them, and the merging of the nodes that a model
//! asks to connect.

use std::collections::HashMap;

/// The tolerance within which two points coincide: 1e-9 of the extent of `points` (the
/// larger side of their bounding box), so that it scales with the units of the model and
/// does not depend on where its origin is (a model drawn at a site's grid coordinates, 4e6 m
/// from the origin, has the tolerance of the same model at the origin). It is never below
/// the round-off of the coordinates themselves (4 ε of the largest in magnitude).
///
/// ```
/// use unilateral_fem::mesh::coincidence_tolerance;
/// let here = coincidence_tolerance(&[[0.0, 0.0], [10.0, 2.0]]);
/// let far = coincidence_tolerance(&[[5e5, 4e6], [5e5 + 10.0, 4e6 + 2.0]]);
/// assert_eq!(here, 1e-8);
/// assert_eq!(far, 1e-8);
/// ```
pub fn coincidence_tolerance(points: &[[f64; 2]]) -> f64 {
    let (extent, largest) = extent(points);
    (1e-9 * extent)
        .max(4.0 * f64::EPSILON * largest)
        .max(1e-300)
}

/// The larger side of the bounding box of `points`, and their largest coordinate in
/// magnitude (both 0 for no points).
pub fn extent(points: &[[f64; 2]]) -> (f64, f64) {
    let Some(first) = points.first() else {
        return (0.0, 0.0);
    };
    let (mut lo, mut hi) = (*first, *first);
    for p in points {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let largest = lo.iter().chain(&hi).fold(0.0f64, |a, v| a.max(v.abs()));
    ((hi[0] - lo[0]).max(hi[1] - lo[1]), largest)
}

/// Finds the points of a subset of a list that lie near a given point: within `tol` in each
/// coordinate. A uniform grid of cells of four times the tolerance holds the subset, so a
/// query reads the 3 × 3 cells around the point only.
///
/// ```
/// use unilateral_fem::mesh::PointIndex;
/// let points = [[0.0, 0.0], [1.0, 0.0], [1.0 + 1e-12, 0.0], [2.0, 0.0]];
/// let index = PointIndex::new(&points, &[1, 2, 3], 1e-9);
/// assert_eq!(index.near([1.0, 0.0]), [1, 2]);
/// assert!(index.near([0.0, 0.0]).is_empty()); // point 0 is not in the subset
/// ```
#[derive(Debug, Clone)]
pub struct PointIndex {
    cells: HashMap<(i64, i64), Vec<usize>>,
    points: Vec<[f64; 2]>,
    tol: f64,
}

impl PointIndex {
    /// Indexes the points `subset` (indices into `all`) with the tolerance `tol > 0`.
    pub fn new(all: &[[f64; 2]], subset: &[usize], tol: f64) -> Self {
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        let cell = 4.0 * tol;
        for &i in subset {
            let p = all[i];
            cells
                .entry(((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64))
                .or_default()
                .push(i);
        }
        Self {
            cells,
            points: all.to_vec(),
            tol,
        }
    }

    /// The indexed points within the tolerance of `p` in each coordinate, in increasing order.
    pub fn near(&self, p: [f64; 2]) -> Vec<usize> {
        let cell = 4.0 * self.tol;
        let (cx, cy) = ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64);
        let mut out = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(v) = self.cells.get(&(cx + dx, cy + dy)) {
                    for &i in v {
                        let q = self.points[i];
                        if (q[0] - p[0]).abs() <= self.tol && (q[1] - p[1]).abs() <= self.tol {
                            out.push(i);
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// The merging of nodes into classes (union–find): each class is represented by its smallest
/// node, so numbering the representatives in order keeps the order of first appearance.
///
/// ```
/// use unilateral_fem::mesh::NodeMerge;
/// let mut m = NodeMerge::new(4);
/// m.union(3, 1);
/// m.union(1, 2);
/// assert_eq!((0..4).map(|i| m.find(i)).collect::<Vec<_>>(), [0, 1, 1, 1]);
/// ```
#[derive(Debug, Clone, Default)]
pub struct NodeMerge {
    parent: Vec<usize>,
}

impl NodeMerge {
    /// `n` nodes, each in a class of its own.
    pub fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
        }
    }

    /// Adds a node in a class of its own; returns its index.
    pub fn push(&mut self) -> usize {
        let i = self.parent.len();
        self.parent.push(i);
        i
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Whether there is no node.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// The representative of the class of `i` (its smallest node).
    pub fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Merges the classes of `a` and `b`.
    pub fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.parent[a.max(b)] = a.min(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{coincidence_tolerance, NodeMerge, PointIndex};

    /// Hand values: the tolerance is 1e-9 of the bounding box's larger side (here 1003, from
    /// x = −3 to 1000); points within it in both coordinates are found, one outside is not,
    /// whatever cell it falls in.
    #[test]
    fn near_points_within_the_tolerance() {
        let pts = [
            [0.0, 0.0],
            [1000.0, 0.0],
            [1000.0, 6e-7],
            [1000.0, 2e-6],
            [-3.0, 2.0],
        ];
        let tol = coincidence_tolerance(&pts);
        assert!((tol - 1.003e-6).abs() <= 1e-20, "{tol}");
        let index = PointIndex::new(&pts, &[0, 1, 2, 3, 4], tol);
        assert_eq!(index.near([1000.0, 0.0]), [1, 2]);
        assert_eq!(index.near([1000.0, 1.5e-6]), [2, 3]);
        assert_eq!(index.near([-3.0, 2.0 - 0.9e-6]), [4]);
        assert!(index.near([-3.0, 2.0 - 1.1e-6]).is_empty());
    }

    /// The same points far from the origin (a site's grid coordinates) have the same
    /// tolerance; points whose extent is below the round-off of their coordinates get that
    /// round-off.
    #[test]
    fn the_tolerance_does_not_depend_on_the_origin() {
        let pts = [[0.0, 0.0], [10.0, 0.0], [10.0, 2.0]];
        let shifted: Vec<[f64; 2]> = pts.iter().map(|p| [p[0] + 5e5, p[1] + 4e6]).collect();
        assert_eq!(coincidence_tolerance(&pts), 1e-8);
        assert_eq!(coincidence_tolerance(&shifted), 1e-8);
        let tiny = [[4e6, 0.0], [4e6 + 1e-9, 0.0]];
        assert_eq!(
            coincidence_tolerance(&tiny),
            4.0 * f64::EPSILON * (4e6 + 1e-9)
        );
    }

    /// Merged pairs by hand: (4, 2), (2, 5), (1, 3) leave the classes {0}, {1, 3}, {2, 4, 5},
    /// each represented by its smallest node.
    #[test]
    fn merged_classes() {
        let mut m = NodeMerge::new(6);
        m.union(4, 2);
        m.union(2, 5);
        m.union(1, 3);
        m.union(5, 4);
        let roots: Vec<usize> = (0..6).map(|i| m.find(i)).collect();
        assert_eq!(roots, [0, 1, 2, 1, 2, 2]);
        assert_eq!(m.push(), 6);
        assert_eq!(m.find(6), 6);
        assert_eq!(m.len(), 7);
    }
}
