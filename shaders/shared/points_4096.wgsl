// Line sets of 4096 values per workgroup, 16 per thread (lines up to 4096 values).
const VPT: u32 = 16u;
const POINTS_MAX: u32 = 4096u;
