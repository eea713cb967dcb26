//! Test and benchmark harness package for the tribo workspace (see tests/ and benches/).
