//! IDENTIFY-LOOPS (paper 000, Appendix A.2): every loop of at most `l` nodes of a constraint
//! graph, each found once, in canonical form.

/// The loops of at most `max_nodes` nodes of the graph whose node `i` is adjacent to `adj[i]`.
///
/// Paths grow stage by stage from every edge `i < j`; a path is extended by a neighbour `j` of
/// its last node when the path is not yet closed, `j` is not below its first node, and `j` is not
/// already on it (except to close it). A closed path is a loop when its second node is smaller
/// than its penultimate one: this canonical form (smallest node first, then the smaller
/// neighbour) names each loop exactly once. Each loop is returned as its nodes, without the
/// repeated first node, in canonical order; loops come out by size, then lexicographically.
pub fn identify_loops(adj: &[Vec<usize>], max_nodes: usize) -> Vec<Vec<usize>> {
    let mut stage: Vec<Vec<usize>> = Vec::new();
    for (i, next) in adj.iter().enumerate() {
        for &j in next {
            if i < j {
                stage.push(vec![i, j]);
            }
        }
    }
    let mut loops = Vec::new();
    for _ in 2..=max_nodes {
        let mut grown = Vec::new();
        for path in &stage {
            let (first, last) = (path[0], path[path.len() - 1]);
            if first == last {
                continue;
            }
            for &j in adj.get(last).map(Vec::as_slice).unwrap_or(&[]) {
                if first <= j && !path[1..].contains(&j) {
                    let mut p = path.clone();
                    p.push(j);
                    grown.push(p);
                }
            }
        }
        for p in &grown {
            let n = p.len();
            if p[0] == p[n - 1] && n >= 4 && p[1] < p[n - 2] {
                loops.push(p[..n - 1].to_vec());
            }
        }
        stage = grown;
    }
    loops.sort_by(|a, b| a.len().cmp(&b.len()).then_with(|| a.cmp(b)));
    loops
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(n: usize, edges: &[(usize, usize)]) -> Vec<Vec<usize>> {
        let mut adj = vec![Vec::new(); n];
        for &(a, b) in edges {
            adj[a].push(b);
            adj[b].push(a);
        }
        adj
    }

    #[test]
    fn a_triangle_is_found_once() {
        let adj = graph(3, &[(0, 1), (1, 2), (2, 0)]);
        assert_eq!(identify_loops(&adj, 3), vec![vec![0, 1, 2]]);
    }

    #[test]
    fn the_ten_bar_after_its_chains() {
        // Kramer's Fig. 8, renumbered: 0 = 11 (ground), 1 = 12, 2 = 13, 3 = 5, 4 = 6, 5 = 8,
        // 6 = 9. Loops of up to 3 nodes: only 8-9-13; larger ones appear at 4 nodes.
        let adj = graph(
            7,
            &[
                (0, 1),
                (0, 4),
                (1, 3),
                (1, 2),
                (3, 5),
                (3, 4),
                (5, 6),
                (6, 2),
                (2, 5),
            ],
        );
        assert_eq!(identify_loops(&adj, 3), vec![vec![2, 5, 6]]);
        let four = identify_loops(&adj, 4);
        assert!(four.contains(&vec![1, 2, 5, 3]), "{four:?}");
        assert!(four.contains(&vec![0, 1, 3, 4]), "{four:?}");
    }

    #[test]
    fn trees_have_no_loops() {
        let adj = graph(4, &[(0, 1), (1, 2), (1, 3)]);
        assert!(identify_loops(&adj, 4).is_empty());
    }
}
