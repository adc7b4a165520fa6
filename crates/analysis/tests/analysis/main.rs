//! Integration tests of shadowlab-analysis (work in progress).
