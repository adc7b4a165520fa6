//! # shadowlab-analysis: what a shadow-map technique costs and buys, measured (work in progress)
