#include <rbc_ifem/reference/axisymmetric_sphere_in_tube.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  namespace
  {
    /// Boundary ids of the meridian mesh.
    enum MeridianBoundary : types::boundary_id
    {
      axis   = 1, ///< r = 0: symmetry, u_r = 0
      wall   = 2, ///< r = R
      ends   = 3, ///< z = ±L, far from the sphere
      sphere = 4  ///< the sphere's surface
    };

    constexpr types::manifold_id sphere_manifold = 0, blend_manifold = 1;

    /**
     * The meridian half-plane of the tube (R = 1, z along x, r along y) with
     * the half disc of radius @p lambda cut out at the origin; see
     * axisymmetric_sphere_in_tube().
     */
    void
    create_meridian_mesh(Triangulation<2> &triangulation,
                         const double      lambda,
                         const double      half_length)
    {
      std::vector<Point<2>>    vertices;
      std::vector<CellData<2>> cells;
      const auto add_cell = [&](const std::array<Point<2>, 4> &corners) {
        CellData<2> cell;
        for (unsigned int v = 0; v < 4; ++v)
          {
            cell.vertices[v] = vertices.size();
            vertices.push_back(corners[v]);
          }
        cells.push_back(cell);
      };

      // Four cells between the half circle and the square [-1, 1] x [0, 1],
      // each spanning 45 degrees; their second coordinate runs along the arc.
      const std::array<Point<2>, 5> square = {{Point<2>(1, 0),
                                               Point<2>(1, 1),
                                               Point<2>(0, 1),
                                               Point<2>(-1, 1),
                                               Point<2>(-1, 0)}};
      for (unsigned int k = 0; k < 4; ++k)
        {
          const double angle = k * numbers::PI / 4,
                       next  = (k + 1) * numbers::PI / 4;
          add_cell(
            {{Point<2>(lambda * std::cos(angle), lambda * std::sin(angle)),
              square[k],
              Point<2>(lambda * std::cos(next), lambda * std::sin(next)),
              square[k + 1]}});
        }
      // Cells of about 1 x 1 from the square out to both ends.
      const unsigned int n_end_cells =
        std::max(1., std::round(half_length - 1.));
      const double dz = (half_length - 1.) / n_end_cells;
      for (unsigned int j = 0; j < n_end_cells; ++j)
        for (const double side : {-1., 1.})
          {
            const double z0 = side * (1. + j * dz),
                         z1 = side * (1. + (j + 1) * dz);
            add_cell({{Point<2>(std::min(z0, z1), 0),
                       Point<2>(std::max(z0, z1), 0),
                       Point<2>(std::min(z0, z1), 1),
                       Point<2>(std::max(z0, z1), 1)}});
          }

      SubCellData               no_subcell_data;
      std::vector<unsigned int> all_vertices;
      GridTools::delete_duplicated_vertices(vertices,
                                            cells,
                                            no_subcell_data,
                                            all_vertices);
      GridTools::consistently_order_cells(cells);
      triangulation.create_triangulation(vertices, cells, no_subcell_data);

      const double tolerance = 1e-10;
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          if (cell->center().norm() < 1.)
            cell->set_manifold_id(blend_manifold);
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                const Point<2> c = face->center();
                if (std::abs(c[1]) < tolerance)
                  face->set_boundary_id(axis);
                else if (std::abs(c[1] - 1.) < tolerance)
                  face->set_boundary_id(wall);
                else if (std::abs(std::abs(c[0]) - half_length) < tolerance)
                  face->set_boundary_id(ends);
                else
                  {
                    face->set_boundary_id(sphere);
                    face->set_manifold_id(sphere_manifold);
                  }
              }
        }
      triangulation.set_manifold(sphere_manifold, PolarManifold<2>(Point<2>()));
      TransfiniteInterpolationManifold<2> blend;
      blend.initialize(triangulation);
      triangulation.set_manifold(blend_manifold, blend);
    }

    /// Poiseuille flow of centre-line speed 1 in the tube of radius 1: (1 - r²,
    /// 0, 0).
    class Poiseuille : public Function<2>
    {
    public:
      Poiseuille()
        : Function<2>(3)
      {}

      double
      value(const Point<2> &p, const unsigned int component) const override
      {
        return component == 0 ? 1. - p[1] * p[1] : 0.;
      }
    };

    /**
     * Axisymmetric Stokes flow (μ = 1) on the meridian mesh, Q2-Q1: the
     * operator, assembled without constraints so that its residual at the
     * sphere's unknowns is the force on the sphere, and the solve for given
     * velocities on the tube's ends and wall and on the sphere. The same
     * unknowns are prescribed in every problem, only their values differ, so
     * the constrained operator is factorized once.
     */
    class MeridianStokes
    {
    public:
      MeridianStokes(const double       lambda,
                     const unsigned int n_refinements,
                     const double       half_length)
        : fe(FE_Q<2>(2), 2, FE_Q<2>(1), 1)
        , mapping(3)
        , dof_handler(triangulation)
      {
        create_meridian_mesh(triangulation, lambda, half_length);
        triangulation.refine_global(n_refinements);
        dof_handler.distribute_dofs(fe);
        DynamicSparsityPattern dsp(dof_handler.n_dofs());
        DoFTools::make_sparsity_pattern(dof_handler, dsp);
        sparsity_pattern.copy_from(dsp);
        operator_matrix.reinit(sparsity_pattern);
        assemble_operator();
        factorize_constrained_operator();
      }

      /**
       * The axial force on the sphere when the ends carry @p end_velocity, the
       * wall rests and the sphere moves at @p sphere_speed along the axis:
       * -2π times the sum of the momentum residuals of the axial velocity
       * unknowns on the sphere (the weak form's boundary term is the traction
       * the sphere exerts on the fluid, weighted with r).
       */
      double
      axial_force(const Function<2> &end_velocity,
                  const double       sphere_speed) const
      {
        const Vector<double> solution = solve(end_velocity, sphere_speed);
        Vector<double>       residual(solution.size());
        operator_matrix.vmult(residual, solution);

        const FEValuesExtractors::Scalar axial(0);
        const IndexSet                   sphere_dofs =
          DoFTools::extract_boundary_dofs(dof_handler,
                                          fe.component_mask(axial),
                                          {MeridianBoundary::sphere});
        double sum = 0;
        for (const auto i : sphere_dofs)
          sum += residual[i];
        return -2. * numbers::PI * sum;
      }

      unsigned int
      n_cells() const
      {
        return triangulation.n_active_cells();
      }

      unsigned int
      n_dofs() const
      {
        return dof_handler.n_dofs();
      }

    private:
      /**
       * ∫ (2 ε(u):ε(v) - p ∇·v - q ∇·u) r dr dz in cylindrical coordinates,
       * where ε has the hoop strain u_r/r besides the meridian components and
       * ∇·u = ∂u_z/∂z + ∂u_r/∂r + u_r/r.
       */
      void
      assemble_operator()
      {
        const QGauss<2>                      quadrature(fe.degree + 1);
        FEValues<2>                          fe_values(mapping,
                              fe,
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
        const FEValuesExtractors::Vector     velocity(0);
        const FEValuesExtractors::Scalar     pressure(2);
        const unsigned int                   n = fe.n_dofs_per_cell();
        FullMatrix<double>                   cell_matrix(n, n);
        std::vector<types::global_dof_index> dof_indices(n);
        std::vector<SymmetricTensor<2, 2>>   strain(n);
        std::vector<double>                  hoop(n), divergence(n), q(n);

        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            cell_matrix = 0;
            for (const unsigned int k : fe_values.quadrature_point_indices())
              {
                const double r = fe_values.quadrature_point(k)[1];
                for (unsigned int i = 0; i < n; ++i)
                  {
                    strain[i] = fe_values[velocity].symmetric_gradient(i, k);
                    hoop[i]   = fe_values[velocity].value(i, k)[1] / r;
                    divergence[i] =
                      fe_values[velocity].divergence(i, k) + hoop[i];
                    q[i] = fe_values[pressure].value(i, k);
                  }
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    cell_matrix(i, j) +=
                      (2. * (strain[i] * strain[j] + hoop[i] * hoop[j]) -
                       divergence[i] * q[j] - q[i] * divergence[j]) *
                      r * fe_values.JxW(k);
              }
            cell->get_dof_indices(dof_indices);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                operator_matrix.add(dof_indices[i],
                                    dof_indices[j],
                                    cell_matrix(i, j));
          }
      }

      /**
       * The velocities on the boundary, u_r = 0 on the axis, and one pressure
       * value pinned: the velocity is prescribed everywhere else, so the
       * pressure is fixed only up to a constant (the data carry no net flux,
       * so the dropped continuity equation holds anyway).
       */
      AffineConstraints<double>
      boundary_constraints(const Function<2> &end_velocity,
                           const double       sphere_speed) const
      {
        AffineConstraints<double>        constraints;
        const FEValuesExtractors::Vector velocity(0);
        const FEValuesExtractors::Scalar radial(1), pressure(2);
        const ComponentMask velocity_mask = fe.component_mask(velocity);
        const Functions::ZeroFunction<2>     zero(3);
        const Functions::ConstantFunction<2> sphere_velocity(
          std::vector<double>{sphere_speed, 0., 0.});
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 MeridianBoundary::axis,
                                                 zero,
                                                 constraints,
                                                 fe.component_mask(radial));
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 MeridianBoundary::wall,
                                                 zero,
                                                 constraints,
                                                 velocity_mask);
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 MeridianBoundary::ends,
                                                 end_velocity,
                                                 constraints,
                                                 velocity_mask);
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 MeridianBoundary::sphere,
                                                 sphere_velocity,
                                                 constraints,
                                                 velocity_mask);
        const IndexSet pressure_dofs =
          DoFTools::extract_dofs(dof_handler, fe.component_mask(pressure));
        constraints.add_line(*pressure_dofs.begin());
        constraints.close();
        return constraints;
      }

      /// The operator with the prescribed rows and columns replaced by the
      /// identity, factorized.
      void
      factorize_constrained_operator()
      {
        const AffineConstraints<double> constraints =
          boundary_constraints(Functions::ZeroFunction<2>(3), 0.);
        SparseMatrix<double> matrix(sparsity_pattern);
        matrix.copy_from(operator_matrix);
        for (unsigned int i = 0; i < dof_handler.n_dofs(); ++i)
          if (constraints.is_constrained(i))
            {
              for (auto entry = matrix.begin(i); entry != matrix.end(i);
                   ++entry)
                if (entry->column() != i)
                  {
                    entry->value() = 0.;
                    matrix.set(entry->column(), i, 0.);
                  }
              matrix.set(i, i, 1.);
            }
        constrained_operator.initialize(matrix);
      }

      /// The flow for the given boundary velocities: the prescribed values
      /// moved to the right.
      Vector<double>
      solve(const Function<2> &end_velocity, const double sphere_speed) const
      {
        const AffineConstraints<double> constraints =
          boundary_constraints(end_velocity, sphere_speed);
        Vector<double> prescribed(dof_handler.n_dofs()),
          solution(dof_handler.n_dofs());
        constraints.distribute(prescribed);
        operator_matrix.vmult(solution, prescribed);
        solution *= -1.;
        for (unsigned int i = 0; i < dof_handler.n_dofs(); ++i)
          if (constraints.is_constrained(i))
            solution[i] = 0.;
        constrained_operator.solve(solution);
        // The prescribed values: the solve left them zero.
        solution += prescribed;
        return solution;
      }

      Triangulation<2>     triangulation;
      const FESystem<2>    fe;
      const MappingQ<2>    mapping;
      DoFHandler<2>        dof_handler;
      SparsityPattern      sparsity_pattern;
      SparseMatrix<double> operator_matrix;
      SparseDirectUMFPACK  constrained_operator;
    };
  } // namespace

  SphereInTubeDrag
  axisymmetric_sphere_in_tube(const double       lambda,
                              const unsigned int n_refinements,
                              const double       half_length)
  {
    AssertThrow(lambda > 0. && lambda <= 0.9,
                ExcMessage("λ must lie in (0, 0.9]"));
    AssertThrow(half_length >= 2.,
                ExcMessage("the half length must be at least 2 radii"));

    const MeridianStokes stokes(lambda, n_refinements, half_length);
    const double         stokes_drag =
      6. * numbers::PI * lambda; // 6π μ a U, μ = R = U = 1

    SphereInTubeDrag drag;
    drag.towed_drag_factor =
      -stokes.axial_force(Functions::ZeroFunction<2>(3), 1.) / stokes_drag;
    drag.held_drag_factor = stokes.axial_force(Poiseuille(), 0.) / stokes_drag;
    drag.velocity_ratio   = drag.held_drag_factor / drag.towed_drag_factor;
    drag.n_cells          = stokes.n_cells();
    drag.n_dofs           = stokes.n_dofs();
    return drag;
  }
} // namespace rbc_ifem
