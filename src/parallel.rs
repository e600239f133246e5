//! Independent work on all cores. Kernels stay single-threaded (on the 2-core target machine
//! 2-thread dense kernels were slower than 1); what runs concurrently is whole, independent
//! pieces of the pipeline, and results never depend on the number of cores.

/// `f` applied to every item, on up to `available_parallelism` threads, results in item order.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).min(items.len());
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let f = &f;
    let mut out: Vec<Option<R>> = (0..items.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| scope.spawn(move || items.iter().enumerate().skip(t).step_by(threads).map(|(i, x)| (i, f(x))).collect::<Vec<_>>()))
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
