//! Independent work on all cores. Kernels stay single-threaded (on the 2-core target machine
//! 2-thread dense kernels were slower than 1); what runs concurrently is whole, independent
//! pieces of the pipeline, and results never depend on the number of cores.

/// `f` applied to every item, on up to `available_parallelism` threads, results in item order.
/// Items are handed out one at a time to whichever thread is free (their costs vary: a
/// candidate's profile map, a symmetry's polish), so no thread idles while work remains.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).min(items.len());
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let f = &f;
    let next = std::sync::atomic::AtomicUsize::new(0);
    let next = &next;
    let mut out: Vec<Option<R>> = (0..items.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(move || {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(x) = items.get(i) else { return done };
                        done.push((i, f(x)));
                    }
                })
            })
            .collect();
        for h in handles {
            for (i, r) in h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)) {
                out[i] = Some(r);
            }
        }
    });
    out.into_iter().map(|r| r.expect("every item mapped")).collect()
}

/// `(a(), b())`, `a` on a new thread while `b` runs on this one; a panic in `a` is re-raised here.
pub(crate) fn join<A: Send, B>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B) -> (A, B) {
    std::thread::scope(|scope| {
        let h = scope.spawn(a);
        let rb = b();
        (h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)), rb)
    })
}

/// Whether more than one core is available (speculative work is pointless otherwise).
pub(crate) fn available() -> bool {
    std::thread::available_parallelism().map_or(1, |t| t.get()) > 1
}
