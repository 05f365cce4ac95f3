/* The interface between flange (C++20) and Odeint's rosenbrock4, compiled as
   C++17 in src/rosenbrock4.cpp (Boost 1.74's uBLAS does not compile as C++20). */
#ifndef FLANGE_ROSENBROCK4_BRIDGE_H
#define FLANGE_ROSENBROCK4_BRIDGE_H
#ifdef __cplusplus
extern "C" {
#endif
typedef struct flange_stiff_callbacks {
  void* context;
  int n;
  void (*f)(void* context, const double* x, double* dxdt, double t);
  /* J row-major n×n, and ∂f/∂t */
  void (*jacobian)(void* context, const double* x, double* J, double* dfdt, double t);
  void (*observe)(void* context, const double* x, double t); /* may be null */
} flange_stiff_callbacks;

/* Integrates from t0 to t1 with rosenbrock4 (dense output, the given
   tolerances). observe_dt > 0: observe at fixed steps (integrate_const);
   otherwise at every step (integrate_adaptive). Returns the number of steps,
   or -1 if a callback threw. */
long flange_rosenbrock4_integrate(const flange_stiff_callbacks* cb, double* x, double t0, double t1, double dt,
                                  double abs_tol, double rel_tol, double observe_dt);
#ifdef __cplusplus
}
#endif
#endif
