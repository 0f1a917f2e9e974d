//! Fork–join on two OS threads (std only: the work is split into two
//! coarse halves, never into many small tasks).

/// Runs `a` on this thread and `b` on a second one, and returns both
/// results. A panic in `b` (a bug, not an input error) is propagated, as
/// is a failure of the OS to start a thread (like running out of memory).
pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA,
    B: FnOnce() -> RB + Send,
    RB: Send,
{
    std::thread::scope(|scope| {
        let handle = scope.spawn(b);
        let ra = a();
        match handle.join() {
            Ok(rb) => (ra, rb),
            Err(payload) => std::panic::resume_unwind(payload),
        }
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn both_results_come_back() {
        let data = [1, 2, 3, 4];
        let (s1, s2) = super::join(
            || data[..2].iter().sum::<i32>(),
            || data[2..].iter().sum::<i32>(),
        );
        assert_eq!((s1, s2), (3, 7));
    }
}
