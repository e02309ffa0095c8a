#pragma once
// The precision a reused CHOLMOD factor is kept and back-solved in (supernodal_cholesky.hpp):
// single halves the bytes of each back-solve, half (binary16 below the diagonal blocks) nearly
// halves them again; full keeps CHOLMOD's double values.
namespace fissure {

enum class FactorPrecision { single, full, half };

// The name the config key `factor_precision` gives it.
inline const char* factor_precision_name(FactorPrecision p) {
  return p == FactorPrecision::single ? "single" : p == FactorPrecision::half ? "half" : "double";
}

}  // namespace fissure
