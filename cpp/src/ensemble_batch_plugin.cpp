// The SIMD batches compiled for one instruction set, as a plugin of the Python module: built
// once per instruction set (AVX2 + FMA, AVX-512; CMakeLists.txt, "runtime dispatch of the SIMD
// lanes") with hidden symbols, so that nothing in it (the batches, and the inline functions and
// templates they instantiate with the wider instructions) can stand in for the library's own
// portable code. gyrostat._core loads the widest plugin the CPU runs when it is imported
// (bindings/expose_integrate.cpp) and installs its form with ensemble_batch::use; without it,
// the library's own portable form runs. The types passed in and out are the library's: both
// sides are compiled with Eigen's static alignment held at 16 bytes, so their layouts agree.
#include "ensemble_batch.cpp"

extern "C" __attribute__((visibility("default"))) const gyrostat::ensemble_batch::Implementation*
gyrostat_batch_implementation() {
    return &gyrostat::ensemble_batch::compiled();
}
