// Around an include of Boost.Odeint's headers:
//
//   FLANGE_ODEINT_INCLUDES_BEGIN
//   #include <boost/numeric/odeint/…>
//   FLANGE_ODEINT_INCLUDES_END
//
// Odeint's steppers copy their scratch buffers before first writing them, and
// GCC 12 flags those copies (-Wuninitialized, -Wmaybe-uninitialized) at their
// location in Odeint's headers. The pragmas cover only those headers, not
// flange or user code; other compilers see nothing.
#pragma once
#if defined(__GNUC__) && !defined(__clang__)
#define FLANGE_ODEINT_INCLUDES_BEGIN                                 \
  _Pragma("GCC diagnostic push")                                     \
  _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")              \
  _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")
#define FLANGE_ODEINT_INCLUDES_END _Pragma("GCC diagnostic pop")
#else
#define FLANGE_ODEINT_INCLUDES_BEGIN
#define FLANGE_ODEINT_INCLUDES_END
#endif
