//! A nested-dissection ordering of the bonded stiffness's graph, for the forward-only Schur
//! complement of the condensation.
//!
//! `R = K_zz − YᵀY` with `Y = L⁻¹ P K_Iz` costs what the columns of `Y` reach: the column of a
//! link DOF is non-zero on the path of the elimination tree from its node's DOFs to the root.
//! A minimum-degree ordering of a long strip makes that path long (half the strip on average:
//! the 2000 × 10 block's `Y` would hold a third of a dense `n_i × 2m`); a nested dissection
//! keeps it to the separators above the node, `O(log n)` of them. faer has no nested
//! dissection, so this is one by level structures: a breadth-first search from a
//! pseudo-peripheral vertex (two sweeps), the level at the median vertex as separator (only
//! those of its vertices that touch the next level), the two sides ordered recursively before
//! it. It needs only the graph, no coordinates, so it serves every model; the ordering changes
//! only round-off, never the values of `R` in exact arithmetic.

/// Subgraphs of at most this many vertices are not divided further (kept in their order).
const LEAF: usize = 64;

/// The graph of a symmetric matrix (adjacency lists, no self loops) in compressed rows.
pub(super) struct Graph {
    ptr: Vec<usize>,
    adj: Vec<usize>,
}

impl Graph {
    /// From the row indices of the columns of a symmetric matrix stored as one triangle
    /// (`col_ptr`, `row_idx` in compressed columns).
    pub(super) fn from_triangle(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Self {
        let mut deg = vec![0usize; n];
        for c in 0..n {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                if r != c {
                    deg[r] += 1;
                    deg[c] += 1;
                }
            }
        }
        let mut ptr = vec![0usize; n + 1];
        for v in 0..n {
            ptr[v + 1] = ptr[v] + deg[v];
        }
        let mut fill = ptr[..n].to_vec();
        let mut adj = vec![0usize; ptr[n]];
        for c in 0..n {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                if r != c {
                    adj[fill[r]] = c;
                    fill[r] += 1;
                    adj[fill[c]] = r;
                    fill[c] += 1;
                }
            }
        }
        Graph { ptr, adj }
    }

    fn neighbours(&self, v: usize) -> &[usize] {
        &self.adj[self.ptr[v]..self.ptr[v + 1]]
    }

    fn len(&self) -> usize {
        self.ptr.len() - 1
    }
}

/// The elimination order: `order[k]` is the vertex eliminated `k`-th (faer's forward array).
pub(super) fn nested_dissection(g: &Graph) -> Vec<usize> {
    let n = g.len();
    let mut work = Work {
        member: vec![0; n],
        level: vec![usize::MAX; n],
        stamp: 0,
        queue: Vec::with_capacity(n),
    };
    let mut order = Vec::with_capacity(n);
    // an explicit stack of subgraphs to divide, so that no input can exhaust the call stack;
    // each entry is either a subgraph to divide or a separator to emit after its two sides
    enum Task {
        Divide(Vec<usize>),
        Emit(Vec<usize>),
    }
    let mut stack = vec![Task::Divide((0..n).collect())];
    while let Some(task) = stack.pop() {
        match task {
            Task::Emit(sep) => order.extend(sep),
            Task::Divide(verts) => match work.split(g, verts) {
                Split::Leaf(verts) => order.extend(verts),
                Split::Parts(a, b, sep) => {
                    // popped in reverse: a, then b, then the separator
                    stack.push(Task::Emit(sep));
                    stack.push(Task::Divide(b));
                    stack.push(Task::Divide(a));
                }
            },
        }
    }
    order
}

enum Split {
    Leaf(Vec<usize>),
    /// Two sides and the separator between them (empty between two components).
    Parts(Vec<usize>, Vec<usize>, Vec<usize>),
}

struct Work {
    /// `member[v] == stamp` marks the vertices of the current subgraph.
    member: Vec<u32>,
    level: Vec<usize>,
    stamp: u32,
    queue: Vec<usize>,
}

impl Work {
    /// Breadth-first search from `root` within the current subgraph; leaves the visited
    /// vertices in `queue` (by level) and their levels in `level`.
    fn bfs(&mut self, g: &Graph, root: usize, verts: &[usize]) {
        for &v in verts {
            self.level[v] = usize::MAX;
        }
        self.queue.clear();
        self.queue.push(root);
        self.level[root] = 0;
        let mut head = 0;
        while head < self.queue.len() {
            let v = self.queue[head];
            head += 1;
            let lv = self.level[v];
            for &u in g.neighbours(v) {
                if self.member[u] == self.stamp && self.level[u] == usize::MAX {
                    self.level[u] = lv + 1;
                    self.queue.push(u);
                }
            }
        }
    }

    fn split(&mut self, g: &Graph, verts: Vec<usize>) -> Split {
        if verts.len() <= LEAF {
            return Split::Leaf(verts);
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.member.iter_mut().for_each(|m| *m = u32::MAX);
            self.stamp = 1;
        }
        for &v in &verts {
            self.member[v] = self.stamp;
        }
        self.bfs(g, verts[0], &verts);
        if self.queue.len() < verts.len() {
            // not connected: the component of verts[0], and the rest
            let comp = self.queue.clone();
            let rest = verts
                .iter()
                .copied()
                .filter(|&v| self.level[v] == usize::MAX)
                .collect();
            return Split::Parts(comp, rest, Vec::new());
        }
        // second sweep from the farthest vertex: a pseudo-peripheral start
        let far = *self.queue.last().expect("non-empty");
        self.bfs(g, far, &verts);
        let depth = self.level[*self.queue.last().expect("non-empty")];
        if depth < 2 {
            return Split::Leaf(verts);
        }
        let mid = self.level[self.queue[self.queue.len() / 2]].clamp(1, depth - 1);
        let (mut a, mut b, mut sep) = (Vec::new(), Vec::new(), Vec::new());
        for &v in &self.queue {
            let lv = self.level[v];
            if lv < mid {
                a.push(v);
            } else if lv > mid {
                b.push(v);
            } else if g
                .neighbours(v)
                .iter()
                .any(|&u| self.member[u] == self.stamp && self.level[u] == mid + 1)
            {
                sep.push(v);
            } else {
                // touches only levels mid − 1 and mid: it may join side a
                a.push(v);
            }
        }
        Split::Parts(a, b, sep)
    }
}

#[cfg(test)]
mod tests {
    use super::{nested_dissection, Graph};

    /// A path of 200 vertices: the order is a permutation, and every separator vertex comes
    /// after the two sides it separates (checked as: in the elimination order, each vertex
    /// has at most two neighbours eliminated after it, and the last vertex splits the path
    /// near its middle — the reference is the definition of a dissection of a path).
    #[test]
    fn a_path_is_dissected_at_its_middle() {
        let n = 200;
        // lower triangle of a tridiagonal matrix
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for c in 0..n {
            row_idx.push(c);
            if c + 1 < n {
                row_idx.push(c + 1);
            }
            col_ptr.push(row_idx.len());
        }
        let g = Graph::from_triangle(n, &col_ptr, &row_idx);
        let order = nested_dissection(&g);
        let mut seen = vec![false; n];
        for &v in &order {
            assert!(!seen[v], "vertex {v} twice");
            seen[v] = true;
        }
        assert!(seen.iter().all(|s| *s));
        let last = *order.last().unwrap();
        assert!((n / 2 - 2..=n / 2 + 2).contains(&last), "separator {last}");
    }

    /// Two disconnected paths of 40 vertices each are ordered one after the other, with
    /// no separator (a separator between components would be fill for nothing).
    #[test]
    fn components_are_ordered_apart() {
        let n = 80;
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for c in 0..n {
            row_idx.push(c);
            if c + 1 < n && c + 1 != 40 {
                row_idx.push(c + 1);
            }
            col_ptr.push(row_idx.len());
        }
        let g = Graph::from_triangle(n, &col_ptr, &row_idx);
        let order = nested_dissection(&g);
        let first: Vec<bool> = order.iter().map(|&v| v < 40).collect();
        let switches = first.windows(2).filter(|w| w[0] != w[1]).count();
        assert_eq!(switches, 1, "{order:?}");
    }
}
