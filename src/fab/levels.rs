//! Precedence levels of a DAG, as the process-planning seed orders its
//! macro-operations: an operation with no predecessor is on level 1, every
//! other on **1 + the largest level of its predecessors**, so all operations of
//! one level can run at once. A cycle is returned as the nodes on it.

/// The level of each of `n` nodes under `edges` (`(before, after)` pairs).
///
/// # Errors
///
/// The nodes of one cycle, in order along it, the first repeated at the end,
/// when the edges are not acyclic.
pub fn levels(n: usize, edges: &[(usize, usize)]) -> Result<Vec<u32>, Vec<usize>> {
    let mut successors = vec![Vec::new(); n];
    let mut waiting = vec![0usize; n];
    for &(a, b) in edges {
        successors[a].push(b);
        waiting[b] += 1;
    }
    let mut level = vec![0u32; n];
    let mut ready: Vec<usize> = (0..n).filter(|&i| waiting[i] == 0).collect();
    for &i in &ready {
        level[i] = 1;
    }
    let mut done = 0;
    while let Some(i) = ready.pop() {
        done += 1;
        for &j in &successors[i] {
            level[j] = level[j].max(level[i] + 1);
            waiting[j] -= 1;
            if waiting[j] == 0 {
                ready.push(j);
            }
        }
    }
    if done == n {
        return Ok(level);
    }
    // Every node still waiting has a waiting predecessor: walk back until a
    // node repeats.
    let mut predecessor = vec![None; n];
    for &(a, b) in edges {
        if waiting[a] > 0 && waiting[b] > 0 && predecessor[b].is_none() {
            predecessor[b] = Some(a);
        }
    }
    let start = (0..n).find(|&i| waiting[i] > 0).unwrap_or(0);
    let mut seen = vec![usize::MAX; n];
    let mut path = Vec::new();
    let mut at = start;
    while seen[at] == usize::MAX {
        seen[at] = path.len();
        path.push(at);
        match predecessor[at] {
            Some(p) => at = p,
            None => break,
        }
    }
    let mut cycle: Vec<usize> = path[seen[at].min(path.len())..].to_vec();
    cycle.reverse();
    if let Some(&first) = cycle.first() {
        cycle.push(first);
    }
    Err(cycle)
}

#[cfg(test)]
mod tests {
    use super::levels;

    #[test]
    fn level_is_one_more_than_the_deepest_predecessor() {
        // 0 → 1 → 3, 2 → 3, 0 → 3: 3 waits for 1 (level 2).
        let l = levels(5, &[(0, 1), (1, 3), (2, 3), (0, 3)]).unwrap();
        assert_eq!(l, vec![1, 2, 1, 3, 1]);
    }

    #[test]
    fn a_cycle_is_returned_in_order() {
        let c = levels(4, &[(0, 1), (1, 2), (2, 3), (3, 1)]).unwrap_err();
        assert_eq!(c.len(), 4, "{c:?}");
        assert_eq!(c.first(), c.last());
        let mut members = c[..3].to_vec();
        members.sort();
        assert_eq!(members, vec![1, 2, 3]);
        // Consecutive nodes are edges.
        let edges = [(0, 1), (1, 2), (2, 3), (3, 1)];
        assert!(c.windows(2).all(|w| edges.contains(&(w[0], w[1]))), "{c:?}");
    }
}
