//! Memory a run will need, asked of the system before the work starts: a grid, an image or
//! a renderer larger than the machine can give is refused with one line, not aborted by
//! the allocator part-way (`docs/reliability.md`).

use crate::args::CliResult;

/// Refuses `what` when the system cannot give `bytes` more: the address space is reserved
/// (`try_reserve`, never touched, so it costs no memory) and given back at once. `fix`
/// says what to change.
pub fn check(bytes: u64, what: &str, fix: &str) -> CliResult<()> {
    let mut probe: Vec<u8> = Vec::new();
    let fits = usize::try_from(bytes).is_ok_and(|n| probe.try_reserve_exact(n).is_ok());
    if fits {
        Ok(())
    } else {
        Err(format!(
            "{what}: needs about {:.1} GiB of memory, more than this system gives; {fix}",
            bytes as f64 / (1u64 << 30) as f64
        ))
    }
}

/// Refuses a grid of `params` when the system cannot give `bytes_per_node` for each of its
/// nodes plus `extra` bytes: what `command` measured at most (peak resident memory per node,
/// rounded up) with the work it was asked for. Called before the surface is built.
pub fn check_grid(
    params: &springwater::Params,
    bytes_per_node: u64,
    extra: u64,
    command: &str,
) -> CliResult<()> {
    // A model the library refuses is reported by building it, in the library's words.
    if params.validate().is_err() {
        return Ok(());
    }
    let nodes = params.cols as u64 * params.rows as u64;
    check(
        nodes.saturating_mul(bytes_per_node).saturating_add(extra),
        &format!("{command} --size {}x{}", params.cols, params.rows),
        "use a smaller --size",
    )
}
