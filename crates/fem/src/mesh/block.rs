//! The structured grid of a rectangular block.

/// The nodes and 4-node cells of a rectangle divided into `nx × ny` equal cells.
///
/// Node `(i, j)` (`0 ≤ i ≤ nx` along x, `0 ≤ j ≤ ny` along y) is at
/// `origin + (width·i/nx, height·j/ny)` and has the index [`BlockGrid::index`]
/// `= j·(nx + 1) + i`: the nodes are listed row by row from the bottom.
///
/// ```
/// use unilateral_fem::mesh::BlockGrid;
/// let g = BlockGrid::new([1.0, 2.0], 2.0, 1.0, 2, 1);
/// assert_eq!(g.points().len(), 6);
/// assert_eq!(g.points()[4], [2.0, 3.0]);
/// assert_eq!(g.cells()[1], [1, 2, 5, 4]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BlockGrid {
    nx: usize,
    ny: usize,
    points: Vec<[f64; 2]>,
}

impl BlockGrid {
    /// The grid of the rectangle with lower-left corner `origin`, `width` along x and `height`
    /// along y, divided into `nx` cells along x and `ny` along y (both at least 1).
    pub fn new(origin: [f64; 2], width: f64, height: f64, nx: usize, ny: usize) -> Self {
        let mut points = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                points.push([
                    origin[0] + width * i as f64 / nx as f64,
                    origin[1] + height * j as f64 / ny as f64,
                ]);
            }
        }
        Self { nx, ny, points }
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Cells along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// The index of node `(i, j)`.
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * (self.nx + 1) + i
    }

    /// The node coordinates, in index order.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The cells, counter-clockwise from the lower-left node: cell `(i, j)` (lower-left node
    /// `(i, j)`) is `[(i, j), (i+1, j), (i+1, j+1), (i, j+1)]`, listed row by row from the
    /// bottom.
    pub fn cells(&self) -> Vec<[usize; 4]> {
        let mut out = Vec::with_capacity(self.nx * self.ny);
        for j in 0..self.ny {
            for i in 0..self.nx {
                out.push([
                    self.index(i, j),
                    self.index(i + 1, j),
                    self.index(i + 1, j + 1),
                    self.index(i, j + 1),
                ]);
            }
        }
        out
    }

    /// The nodes of the column `i` (bottom to top).
    pub fn column(&self, i: usize) -> Vec<usize> {
        (0..=self.ny).map(|j| self.index(i, j)).collect()
    }

    /// The nodes of the row `j` (left to right).
    pub fn row(&self, j: usize) -> Vec<usize> {
        (0..=self.nx).map(|i| self.index(i, j)).collect()
    }

    /// The named edges and corners of the block: `left`, `right`, `bottom`, `top` (in the
    /// order of [`BlockGrid::column`] and [`BlockGrid::row`]) and `bottom_left`,
    /// `bottom_right`, `top_left`, `top_right`.
    pub fn boundary(&self) -> [(&'static str, Vec<usize>); 8] {
        let (nx, ny) = (self.nx, self.ny);
        [
            ("left", self.column(0)),
            ("right", self.column(nx)),
            ("bottom", self.row(0)),
            ("top", self.row(ny)),
            ("bottom_left", vec![self.index(0, 0)]),
            ("bottom_right", vec![self.index(nx, 0)]),
            ("top_left", vec![self.index(0, ny)]),
            ("top_right", vec![self.index(nx, ny)]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::BlockGrid;

    /// Hand values: a 3 × 2 block of width 3 and height 1 from (−1, 0): 12 nodes, 6 cells,
    /// node (i, j) at (−1 + i, j/2).
    #[test]
    fn counts_coordinates_and_cells() {
        let g = BlockGrid::new([-1.0, 0.0], 3.0, 1.0, 3, 2);
        assert_eq!(g.points().len(), 12);
        assert_eq!(g.cells().len(), 6);
        assert_eq!(g.index(2, 1), 6);
        assert_eq!(g.points()[6], [1.0, 0.5]);
        assert_eq!(g.points()[11], [2.0, 1.0]);
        // the first cell, counter-clockwise from the lower left; the last one
        assert_eq!(g.cells()[0], [0, 1, 5, 4]);
        assert_eq!(g.cells()[5], [6, 7, 11, 10]);
    }

    /// Hand values of the edges and corners of the same block.
    #[test]
    fn edges_and_corners() {
        let g = BlockGrid::new([-1.0, 0.0], 3.0, 1.0, 3, 2);
        let b = g.boundary();
        let get = |name: &str| b.iter().find(|(n, _)| *n == name).unwrap().1.clone();
        assert_eq!(get("left"), [0, 4, 8]);
        assert_eq!(get("right"), [3, 7, 11]);
        assert_eq!(get("bottom"), [0, 1, 2, 3]);
        assert_eq!(get("top"), [8, 9, 10, 11]);
        assert_eq!(get("bottom_left"), [0]);
        assert_eq!(get("bottom_right"), [3]);
        assert_eq!(get("top_left"), [8]);
        assert_eq!(get("top_right"), [11]);
    }
}
