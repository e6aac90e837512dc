// Shared by every kernel: the workgroup size (threads), which the host's dispatch grids assume
// (`WORKGROUP` in src/backend/gpu/recorder.rs).
const WG: u32 = 256u;
