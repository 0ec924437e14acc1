//! Independent pieces of work shared out among the cores, their results gathered in order.

/// `f` of every item, in the order of the items: on `threads` scoped threads (each a run of
/// consecutive items) when `threads > 1`, else on the calling thread. The items are
/// independent, so the result does not depend on the number of threads; a panic in a
/// thread is resumed on the caller.
pub(crate) fn map_in_order<T: Send, R: Send>(
    items: &mut [T],
    threads: usize,
    f: impl Fn(&mut T) -> R + Sync,
) -> Vec<R> {
    if threads <= 1 || items.len() <= 1 {
        return items.iter_mut().map(f).collect();
    }
    let chunk = items.len().div_ceil(threads);
    let f = &f;
    std::thread::scope(|scope| {
        let handles: Vec<_> = items
            .chunks_mut(chunk)
            .map(|part| scope.spawn(move || part.iter_mut().map(f).collect::<Vec<_>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}
