//! Independent work on all cores, on rayon's work-stealing pool. Kernels stay single-threaded
//! (on the 2-core target machine 2-thread dense kernels were slower than 1); what runs
//! concurrently is whole, independent pieces of the pipeline (candidates, maps, ranges of
//! vertices), and results never depend on the number of cores: every primitive returns the
//! serial result, in order.
//!
//! Why a pool: the maps stage has hundreds of parallel regions of 0.1–1 ms. Spawning scoped
//! threads for each cost about 80 µs per region on the 2-core VM (a spawn and a futex wake-up
//! of the other virtual CPU); rayon's idle workers are woken in 10–20 µs, and nested regions
//! (a vertex loop inside a candidate's map, itself one of several on all cores) cost next to
//! nothing when the cores are busy: the inner work just runs where it is.

use rayon::prelude::*;

/// The number of cores, asked once: `available_parallelism` reads the cgroup's quota files
/// on every call (about ten system calls).
pub(crate) fn cores() -> usize {
    static CORES: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |t| t.get()))
}

/// `f` applied to every item, results in item order. Items are handed out one at a time (their
/// costs vary: a candidate's profile map, a symmetry's polish), so no core idles while work
/// remains.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync + Send) -> Vec<R> {
    if cores() <= 1 || items.len() <= 1 {
        return items.iter().map(f).collect();
    }
    items.par_iter().with_max_len(1).map(f).collect()
}

/// `f(range)` over `0..len` cut into one contiguous range per core, results in range order: for
/// loops over vertices whose items are independent and cheap (a range amortises the hand-off).
pub(crate) fn chunks<R: Send>(len: usize, f: impl Fn(std::ops::Range<usize>) -> R + Sync + Send) -> Vec<R> {
    // Below this many items per range a loop is not worth splitting.
    const MIN_CHUNK: usize = 256;
    let parts = cores().min(len.div_ceil(MIN_CHUNK)).max(1);
    if parts <= 1 {
        return vec![f(0..len)];
    }
    let size = len.div_ceil(parts);
    let ranges: Vec<std::ops::Range<usize>> = (0..len).step_by(size).map(|a| a..(a + size).min(len)).collect();
    map(&ranges, |r| f(r.clone()))
}

/// `(a(), b())`, possibly on two cores; a panic in either is re-raised here.
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    if cores() <= 1 {
        return (a(), b());
    }
    rayon::join(a, b)
}

/// `work(relay)` on a thread of the pool, with `progress` called on this thread: each
/// `relay(fraction)` inside `work` hands the fraction over, waits, and returns what
/// `progress` answered here. Returns `work`'s result (a panic in `work` is re-raised here).
///
/// Why: a parallel region entered from a thread outside the pool queues its work and puts
/// that thread to sleep until a pool thread, possibly asleep itself, wakes and takes it; on the
/// 2-core VM waking a parked virtual CPU takes 0.3–4 ms, and the maps stage enters hundreds of
/// regions. From a pool thread the region's first half runs at once where it is, and the
/// other core joins when it is awake (the whole detection 9% faster at 5k). Callers already on
/// a pool thread, and machines with one core, run `work` directly.
pub(crate) fn on_pool<R: Send>(progress: &mut dyn FnMut(f64) -> bool, work: impl FnOnce(&mut dyn FnMut(f64) -> bool) -> R + Send) -> R {
    if cores() <= 1 || rayon::current_thread_index().is_some() {
        return work(progress);
    }
    enum Message<R> {
        Progress(f64),
        Done(R),
    }
    let (to_caller, from_work) = std::sync::mpsc::channel::<Message<R>>();
    let (to_work, answers) = std::sync::mpsc::channel::<bool>();
    let result = rayon::in_place_scope(|scope| {
        scope.spawn(move |_| {
            let mut relay = |f: f64| to_caller.send(Message::Progress(f)).is_ok() && answers.recv().unwrap_or(false);
            let result = work(&mut relay);
            // The receiver lives until this message arrives.
            let _ = to_caller.send(Message::Done(result));
        });
        loop {
            match from_work.recv() {
                Ok(Message::Progress(f)) => {
                    // The worker waits for this answer (it is gone only after a panic).
                    let _ = to_work.send(progress(f));
                }
                Ok(Message::Done(result)) => return Some(result),
                // `work` panicked: the scope re-raises its panic when it ends.
                Err(_) => return None,
            }
        }
    });
    result.expect("a worker that ends without a result has panicked, and the scope re-raised it")
}

/// Whether more than one core is available (speculative work is pointless otherwise).
pub(crate) fn available() -> bool {
    cores() > 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Results are in order whatever the threads, nested calls included.
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
