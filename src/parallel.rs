//! Independent work on all cores. Kernels stay single-threaded (on the 2-core target machine
//! 2-thread dense kernels were slower than 1); what runs concurrently is whole, independent
//! pieces of the pipeline, and results never depend on the number of cores.
//!
//! **Only the outermost level runs in parallel.** Work started inside a parallel region (a
//! candidate's profile map, among others on all cores; a speculative refinement) runs on its
//! own thread, serially: the cores are busy already, and nested threads would only compete for
//! them. The same functions called from a serial stretch (one map to refine or polish) use
//! every core. Every primitive gives the serial result, so which level ran in parallel never
//! changes a result.

use std::cell::Cell;

thread_local! {
    /// Whether this thread runs inside a parallel region.
    static NESTED: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with this thread marked as inside a parallel region.
fn nested<R>(f: impl FnOnce() -> R) -> R {
    let was = NESTED.with(|n| n.replace(true));
    let r = f();
    NESTED.with(|n| n.set(was));
    r
}

/// The number of cores, asked once: `available_parallelism` reads the cgroup's quota files
/// on every call (about ten system calls; the maps stage has hundreds of parallel regions).
pub(crate) fn cores() -> usize {
    static CORES: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |t| t.get()))
}

/// Threads for `items` pieces of work here: 1 inside a parallel region.
fn threads_for(items: usize) -> usize {
    if NESTED.with(Cell::get) {
        return 1;
    }
    cores().min(items)
}

/// `f` applied to every item, on up to `available_parallelism` threads, results in item order.
/// Items are handed out one at a time to whichever thread is free (their costs vary: a
/// candidate's profile map, a symmetry's polish), so no thread idles while work remains.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = threads_for(items.len());
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
                    nested(|| {
                        let mut done = Vec::new();
                        loop {
                            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                            let Some(x) = items.get(i) else { return done };
                            done.push((i, f(x)));
                        }
                    })
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

/// `f(range)` over `0..len` cut into one contiguous range per available thread (one range
/// inside a parallel region), results in range order: for loops over vertices whose items
/// are independent and cheap (a range amortises the thread).
pub(crate) fn chunks<R: Send>(len: usize, f: impl Fn(std::ops::Range<usize>) -> R + Sync) -> Vec<R> {
    // Below this many items per thread a loop is not worth a thread.
    const MIN_CHUNK: usize = 256;
    let threads = threads_for(len.div_ceil(MIN_CHUNK)).max(1);
    let size = len.div_ceil(threads).max(1);
    let ranges: Vec<std::ops::Range<usize>> = (0..len).step_by(size).map(|a| a..(a + size).min(len)).collect();
    if ranges.len() <= 1 {
        return vec![f(0..len)];
    }
    map(&ranges, |r| f(r.clone()))
}

/// `(a(), b())`, `a` on a new thread while `b` runs on this one; a panic in `a` is re-raised
/// here. Inside a parallel region both run here, one after the other.
pub(crate) fn join<A: Send, B>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B) -> (A, B) {
    if threads_for(2) <= 1 {
        return (a(), b());
    }
    std::thread::scope(|scope| {
        let h = scope.spawn(|| nested(a));
        let rb = nested(b);
        (h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)), rb)
    })
}

/// Whether more than one core is available here (speculative work is pointless otherwise,
/// and inside a parallel region the other cores are busy).
pub(crate) fn available() -> bool {
    threads_for(2) > 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Results are in order whatever the threads; nested calls run serially and agree.
    #[test]
    fn map_chunks_and_join_give_the_serial_results() {
        let items: Vec<usize> = (0..1000).collect();
        let serial: Vec<usize> = items.iter().map(|x| x * x).collect();
        assert_eq!(map(&items, |x| x * x), serial);
        let inner = map(&[0usize, 1], |&k| chunks(1000, |r| r.map(|x| x * x + k).sum::<usize>()).into_iter().sum::<usize>());
        let total: usize = serial.iter().sum();
        assert_eq!(inner, vec![total, total + 1000]);
        let parts = chunks(1000, |r| r.map(|x| x * x).collect::<Vec<_>>());
        assert_eq!(parts.concat(), serial);
        assert_eq!(chunks(0, |r| r.len()), vec![0]);
        let (a, b) = join(|| map(&items, |x| x + 1), || chunks(10, |r| r.len()));
        assert_eq!(a.len(), 1000);
        assert_eq!(b.iter().sum::<usize>(), 10);
    }
}
