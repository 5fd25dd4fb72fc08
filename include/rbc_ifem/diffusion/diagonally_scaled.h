#ifndef rbc_ifem_diffusion_diagonally_scaled_h
#define rbc_ifem_diffusion_diagonally_scaled_h

namespace rbc_ifem
{
  /**
   * D K D: a linear operator K seen through a diagonal scaling D (stored as
   * a vector of the same layout). The diffusion solvers work on the
   * symmetrically Jacobi-scaled system D K D (D⁻¹ x) = D b, so that their
   * residual weighs the plasma rows as much as the gas rows, whose αD is
   * 10⁵ times larger: unscaled, a residual of 1e-10 left the flow with an
   * error of 1e-4. A preconditioner P of K becomes D⁻¹ P D⁻¹ the same way.
   */
  template <typename Operator, typename VectorType>
  class DiagonallyScaled
  {
  public:
    DiagonallyScaled(const Operator &op, const VectorType &scale)
      : op(op)
      , scale(scale)
      , scaled_src(scale)
    {}

    void
    vmult(VectorType &dst, const VectorType &src) const
    {
      scaled_src = src;
      scaled_src.scale(scale);
      op.vmult(dst, scaled_src);
      dst.scale(scale);
    }

  private:
    const Operator    &op;
    const VectorType  &scale;
    mutable VectorType scaled_src;
  };
} // namespace rbc_ifem

#endif
