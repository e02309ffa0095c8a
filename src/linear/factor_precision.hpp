#pragma once
// The precision a reused CHOLMOD factor is kept and back-solved in (supernodal_cholesky.hpp):
// single halves the bytes of each back-solve; full keeps CHOLMOD's double values.
namespace fissure {

enum class FactorPrecision { single, full };

}  // namespace fissure
