//! # shadowlab-shadow: shadow-map techniques (work in progress)
