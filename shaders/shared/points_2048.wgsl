// Line sets of 2048 values per workgroup, 8 per thread (lines up to 2048 values).
const VPT: u32 = 8u;
const POINTS_MAX: u32 = 2048u;
