//! The default memory budget: what this process may still allocate.
//!
//! Three limits can stop an allocation before the machine runs out, and the budget is the smallest
//! headroom among those that can be read (Linux; elsewhere none can, and the budget is 4 GiB):
//! - the machine's memory available without swapping (`MemAvailable` in `/proc/meminfo`);
//! - the memory cgroup of the process (a container's or a batch job's limit): `memory.max` less
//!   `memory.current` (cgroup v2), or `memory.limit_in_bytes` less `memory.usage_in_bytes` (v1), in the
//!   cgroup `/proc/self/cgroup` names, or at the root of the cgroup mount where that path is not visible
//!   (inside a cgroup namespace); "max" and v1's near-2⁶³ value mean no limit;
//! - the process's address-space limit (`ulimit -v`, `RLIMIT_AS`: the soft limit of "Max address space" in
//!   `/proc/self/limits`) less the address space it already holds (`VmSize` in `/proc/self/status`). An
//!   allocator reserves address space beyond what it touches, so this headroom is a generous bound.
//!
//! A 1.5 GB address-space limit with 23 GB free used to leave the budget at 23 GB, and a history that fit
//! that budget aborted on "memory allocation failed" (defect D21 of issue 37).

use std::fs::read_to_string;

use crate::error::{Error, Result};

/// What `budget` leaves beside `held` bytes already held, for a solve that gets it as its own budget (an enriched
/// problem beside the one it estimates).
///
/// # Errors
/// [`Error::MemoryBudget`] naming `what()` when that is less than 1 MiB, the least budget a solve takes.
pub(crate) fn left_beside(budget: usize, held: f64, what: impl FnOnce() -> String) -> Result<usize> {
    let left = budget as f64 - held;
    if left < (1 << 20) as f64 {
        return Err(Error::MemoryBudget { what: what(), needed: held + (1 << 20) as f64, budget: budget as f64 });
    }
    Ok(left as usize)
}

/// The default memory budget: [`available_memory`], or 4 GiB where it cannot be read; at least 1 MiB.
pub fn default_memory_budget() -> usize {
    available_memory().unwrap_or(4 << 30).max(1 << 20)
}

/// Bytes this process may still allocate: the smallest headroom of the machine, its memory cgroup and its
/// address-space limit (see the module documentation); `None` where none can be read.
pub fn available_memory() -> Option<usize> {
    let machine = read_to_string("/proc/meminfo").ok().and_then(|t| mem_available(&t));
    let address_space = match (read_to_string("/proc/self/limits"), read_to_string("/proc/self/status")) {
        (Ok(limits), Ok(status)) => address_space_headroom(&limits, &status),
        _ => None,
    };
    [machine, cgroup_headroom_here(), address_space].into_iter().flatten().min()
}

/// `MemAvailable` of `/proc/meminfo`, in bytes.
fn mem_available(meminfo: &str) -> Option<usize> {
    kib_field(meminfo, "MemAvailable:")
}

/// The value of a `Name:  1234 kB` line, in bytes.
fn kib_field(text: &str, name: &str) -> Option<usize> {
    let kib: usize = text.lines().find_map(|l| l.strip_prefix(name))?.split_whitespace().next()?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The soft address-space limit of `/proc/self/limits` less `VmSize` of `/proc/self/status`; `None`
/// when the limit is "unlimited".
fn address_space_headroom(limits: &str, status: &str) -> Option<usize> {
    let limit: usize =
        limits.lines().find_map(|l| l.strip_prefix("Max address space"))?.split_whitespace().next()?.parse().ok()?;
    Some(limit.saturating_sub(kib_field(status, "VmSize:").unwrap_or(0)))
}

/// A cgroup's limit less its usage (each file's text); `None` without a limit ("max", or cgroup v1's
/// page-rounded 2⁶³ − 1).
fn cgroup_headroom(limit: &str, usage: &str) -> Option<usize> {
    let limit: u64 = limit.trim().parse().ok()?;
    if limit >= 1 << 62 {
        return None;
    }
    let usage: u64 = usage.trim().parse().unwrap_or(0);
    usize::try_from(limit.saturating_sub(usage)).ok()
}

/// The headroom of this process's memory cgroup (v2, else v1), where one is set and readable.
fn cgroup_headroom_here() -> Option<usize> {
    let cgroups = read_to_string("/proc/self/cgroup").unwrap_or_default();
    let v2 = cgroups.lines().find_map(|l| l.strip_prefix("0::")).unwrap_or("");
    let v1 = cgroups.lines().find_map(|l| l.split_once(":memory:").map(|x| x.1)).unwrap_or("");
    let candidates = [
        (format!("/sys/fs/cgroup{v2}"), "memory.max", "memory.current"),
        ("/sys/fs/cgroup".to_string(), "memory.max", "memory.current"),
        (format!("/sys/fs/cgroup/memory{v1}"), "memory.limit_in_bytes", "memory.usage_in_bytes"),
        ("/sys/fs/cgroup/memory".to_string(), "memory.limit_in_bytes", "memory.usage_in_bytes"),
    ];
    candidates.iter().find_map(|(dir, limit, usage)| {
        let limit = read_to_string(format!("{}/{limit}", dir.trim_end_matches('/'))).ok()?;
        let usage = read_to_string(format!("{}/{usage}", dir.trim_end_matches('/'))).unwrap_or_default();
        cgroup_headroom(&limit, &usage)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_limit_is_read_from_its_text() {
        assert_eq!(mem_available("MemTotal: 100 kB\nMemAvailable:   2048 kB\n"), Some(2 << 20));
        let limits = "Limit  Soft Limit  Hard Limit  Units\nMax address space         1500000000           unlimited            bytes\n";
        assert_eq!(address_space_headroom(limits, "VmSize:\t  100000 kB\n"), Some(1_500_000_000 - 102_400_000));
        let unlimited = "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_space_headroom(unlimited, "VmSize: 1 kB\n"), None);
        assert_eq!(cgroup_headroom("1073741824\n", "73741824\n"), Some(1_000_000_000));
        assert_eq!(cgroup_headroom("max\n", "5\n"), None);
        assert_eq!(cgroup_headroom("9223372036854771712\n", "5\n"), None);
        assert_eq!(cgroup_headroom("100\n", "200\n"), Some(0));
    }

    #[test]
    fn the_budget_is_at_most_what_the_machine_has() {
        if let Some(machine) = read_to_string("/proc/meminfo").ok().and_then(|t| mem_available(&t)) {
            let budget = available_memory().expect("readable where meminfo is");
            // Within what the machine had a moment ago (it may have freed a little since).
            assert!(budget <= machine + (256 << 20), "{budget} > {machine}");
        }
    }
}
