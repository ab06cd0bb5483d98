// How long this process has run, from the kernel's record of its start: what a user who typed the
// command has waited, the dynamic loader and static initialisation included (oracle.json's
// `phases_seconds.process`).
#pragma once

namespace so {

// Seconds since the process started, at the kernel's clock-tick resolution (10 ms on Linux);
// negative where /proc cannot tell.
double processSeconds();

}  // namespace so
