#include <rbc_ifem/base/output.h>
#include <rbc_ifem/membrane/membrane.h>

#include "membrane_internals.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_fe_field.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

namespace rbc_ifem
{
  using namespace MembraneInternals;

  /// What one cell contributes, at positions of type Number.
  template <typename Number>
  struct Membrane::CellTerms
  {
    Number                            in_plane = 0.;
    Number                            area     = 0.;
    Number                            volume   = 0.;
    std::vector<Tensor<1, 3, Number>> laplacian; ///< y_a = ∫ ∇_Γ N_a · ∇_Γ x dA
    std::vector<Number>               mass;   ///< m_a = ∫ N_a dA
    std::vector<Tensor<1, 3, Number>> normal; ///< ∫ N_a n dA
  };

  Membrane::Membrane(const Triangulation<2, 3> &reference_mesh,
                     const MembraneParameters  &parameters,
                     const Membrane            *like)
    : parameters(parameters)
    , elastic_law(make_elastic_law(parameters.law,
                                   parameters.shear_modulus,
                                   parameters.area_dilation_modulus))
    , scalar_fe(parameters.degree)
    , fe(scalar_fe, 3)
    , dof_handler(reference_mesh)
    , quadrature(parameters.degree + 2)
  {
    dof_handler.distribute_dofs(fe);
    tabulate_shape_functions();
    number_nodes(like);
    interpolate_reference_surface();
    measure_reference_surface();
  }

  void
  Membrane::tabulate_shape_functions()
  {
    const unsigned int n_q = quadrature.size(),
                       n_a = scalar_fe.n_dofs_per_cell();
    shape_values.reinit(n_a, n_q);
    shape_gradients.reinit(n_a, n_q);
    for (unsigned int a = 0; a < n_a; ++a)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          shape_values(a, q)    = scalar_fe.shape_value(a, quadrature.point(q));
          shape_gradients(a, q) = scalar_fe.shape_grad(a, quadrature.point(q));
        }
    point_maps.assign(n_q, FullMatrix<double>(9, fe.n_dofs_per_cell()));
    for (unsigned int q = 0; q < n_q; ++q)
      for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
        {
          const auto [e, a]       = fe.system_to_component_index(k);
          point_maps[q](e, k)     = shape_values(a, q);
          point_maps[q](3 + e, k) = shape_gradients(a, q)[0];
          point_maps[q](6 + e, k) = shape_gradients(a, q)[1];
        }
  }

  void
  Membrane::number_nodes(const Membrane *like)
  {
    if (like && like->dof_handler.n_dofs() == dof_handler.n_dofs() &&
        like->numbering->cell_dofs.size() ==
          dof_handler.get_triangulation().n_active_cells())
      {
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        bool                                 same = true;
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(dofs);
            same =
              same &&
              (dofs == like->numbering->cell_dofs[cell->active_cell_index()]);
          }
        if (same)
          {
            numbering = like->numbering;
            return;
          }
      }
    numbering = std::make_shared<Numbering>();
    // Nodes: numbered by the DoF of their x component.
    const unsigned int n_a = scalar_fe.n_dofs_per_cell();
    std::vector<int>   node_of_dof(dof_handler.n_dofs(), -1);
    numbering->component_of_dof.resize(dof_handler.n_dofs());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        cell->get_dof_indices(dofs);
        std::vector<unsigned int> nodes(n_a);
        for (unsigned int k = 0; k < dofs.size(); ++k)
          numbering->component_of_dof[dofs[k]] =
            fe.system_to_component_index(k).first;
        for (unsigned int a = 0; a < n_a; ++a)
          {
            const auto first = dofs[fe.component_to_system_index(0, a)];
            if (node_of_dof[first] < 0)
              {
                node_of_dof[first] = numbering->n_nodes++;
                numbering->node_dofs.push_back(
                  {{first,
                    dofs[fe.component_to_system_index(1, a)],
                    dofs[fe.component_to_system_index(2, a)]}});
              }
            nodes[a] = node_of_dof[first];
          }
        numbering->cell_dofs.push_back(dofs);
        numbering->cell_nodes.push_back(nodes);
      }
    find_cells_around_nodes();
  }

  void
  Membrane::interpolate_reference_surface()
  {
    // X: the support points of the field, on the curved reference surface.
    const MappingQ<2, 3> mapping(std::max(2u, parameters.degree));
    std::map<types::global_dof_index, Point<3>> support_points;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    reference.reinit(dof_handler.n_dofs());
    for (const auto &[dof, point] : support_points)
      reference[dof] = point[component(dof)];
  }

  const Membrane::ReferenceMetric &
  Membrane::reference_metric() const
  {
    if (!metric.jacobian.empty())
      return metric;
    const unsigned int n_q = quadrature.size();
    for (unsigned int c = 0; c < numbering->cell_dofs.size(); ++c)
      {
        const std::vector<double> X = local_positions(c, reference);
        metric.inverse.emplace_back(n_q);
        metric.jacobian.emplace_back(n_q);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            Tensor<1, 3> tangent[2];
            for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
              {
                const auto [d, a] = fe.system_to_component_index(k);
                for (unsigned int alpha = 0; alpha < 2; ++alpha)
                  tangent[alpha][d] += X[k] * shape_gradients(a, q)[alpha];
              }
            Tensor<2, 2> G;
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              for (unsigned int beta = 0; beta < 2; ++beta)
                G[alpha][beta] = tangent[alpha] * tangent[beta];
            metric.inverse[c][q]  = invert(G);
            metric.jacobian[c][q] = std::sqrt(determinant(G));
          }
      }
    return metric;
  }

  void
  Membrane::measure_reference_surface()
  {
    const std::vector<std::vector<double>> &jacobian =
      reference_metric().jacobian;
    for (unsigned int c = 0; c < numbering->cell_dofs.size(); ++c)
      {
        reference_cell_areas.push_back(0.);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          reference_cell_areas[c] += jacobian[c][q] * quadrature.weight(q);
      }
    area0   = area(reference);
    volume0 = volume(reference);
    forget_owner_data();
  }

  void
  Membrane::forget_owner_data()
  {
    metric = ReferenceMetric();
  }

  const DoFHandler<2, 3> &
  Membrane::get_dof_handler() const
  {
    return dof_handler;
  }

  const Vector<double> &
  Membrane::reference_positions() const
  {
    return reference;
  }

  const std::vector<std::array<types::global_dof_index, 3>> &
  Membrane::nodes() const
  {
    return numbering->node_dofs;
  }

  unsigned int
  Membrane::component(const types::global_dof_index dof) const
  {
    return numbering->component_of_dof[dof];
  }

  std::vector<double>
  Membrane::local_positions(const unsigned int    cell,
                            const Vector<double> &x) const
  {
    std::vector<double> local(numbering->cell_dofs[cell].size());
    for (unsigned int k = 0; k < local.size(); ++k)
      local[k] = x[numbering->cell_dofs[cell][k]];
    return local;
  }

  template <typename Number, typename Law>
  Membrane::CellTerms<Number>
  Membrane::cell_terms(const Law                 &law,
                       const unsigned int         cell,
                       const std::vector<Number> &x) const
  {
    const unsigned int n_a = scalar_fe.n_dofs_per_cell();
    CellTerms<Number>  terms;
    terms.laplacian.resize(n_a);
    terms.mass.resize(n_a);
    terms.normal.resize(n_a);

    const ReferenceMetric &G = reference_metric();
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        Tensor<1, 3, Number> position, tangent[2];
        for (unsigned int k = 0; k < x.size(); ++k)
          {
            const auto [d, a] = fe.system_to_component_index(k);
            position[d] += x[k] * shape_values(a, q);
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              tangent[alpha][d] += x[k] * shape_gradients(a, q)[alpha];
          }
        const double               w = quadrature.weight(q);
        const SurfacePoint<Number> point =
          surface_point(tangent, G.inverse[cell][q], G.jacobian[cell][q], w);
        const Number               &dA        = point.dA;
        const Tensor<1, 3, Number> &normal_dA = point.normal_dA;
        terms.in_plane +=
          law.energy_density(point.I1, point.J) * G.jacobian[cell][q] * w;
        terms.area += dA;
        terms.volume += position * normal_dA / 3.;
        for (unsigned int a = 0; a < n_a; ++a)
          {
            terms.mass[a] += shape_values(a, q) * dA;
            terms.normal[a] += shape_values(a, q) * normal_dA;
            // ∇_Γ N_a · ∇_Γ x = g^{αβ} ∂_α N_a ∂_β x
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              for (unsigned int beta = 0; beta < 2; ++beta)
                {
                  const Number weight = point.g_inverse[alpha][beta] *
                                        shape_gradients(a, q)[alpha] * dA;
                  terms.laplacian[a] += weight * tangent[beta];
                }
          }
      }
    return terms;
  }

  Membrane::Sums
  Membrane::sum_cell_terms(
    const Vector<double>                       &x,
    const std::pair<unsigned int, unsigned int> cells) const
  {
    Sums sums;
    sums.laplacian.resize(numbering->n_nodes);
    sums.normal.resize(numbering->n_nodes);
    sums.mass.resize(numbering->n_nodes);
    // The law is chosen once per call, outside the loop over the cells.
    std::visit(
      [&](const auto &law) {
        for (unsigned int c = cells.first; c < cells.second; ++c)
          add_cell_terms(c, cell_terms(law, c, local_positions(c, x)), sums);
      },
      elastic_law);
    return sums;
  }

  Membrane::Sums
  Membrane::sum_cell_terms(const Vector<double> &x) const
  {
    return sum_cell_terms(x, {0, numbering->cell_dofs.size()});
  }

  Membrane::Sums
  Membrane::sum_shared_cell_terms(const Vector<double> &x) const
  {
    Sums sums = sum_cell_terms(x, share(numbering->cell_dofs.size()));
    if (n_ranks(communicator) == 1)
      return sums;
    // One reduction for all sums, packed in one array.
    std::vector<double> packed{sums.in_plane, sums.area, sums.volume};
    packed.reserve(3 + 7 * numbering->n_nodes);
    for (unsigned int i = 0; i < numbering->n_nodes; ++i)
      {
        for (unsigned int e = 0; e < 3; ++e)
          packed.insert(packed.end(),
                        {sums.laplacian[i][e], sums.normal[i][e]});
        packed.push_back(sums.mass[i]);
      }
    add_up_over_ranks(make_array_view(packed), communicator);
    auto value    = packed.begin();
    sums.in_plane = *value++;
    sums.area     = *value++;
    sums.volume   = *value++;
    for (unsigned int i = 0; i < numbering->n_nodes; ++i)
      {
        for (unsigned int e = 0; e < 3; ++e)
          {
            sums.laplacian[i][e] = *value++;
            sums.normal[i][e]    = *value++;
          }
        sums.mass[i] = *value++;
      }
    return sums;
  }

  std::pair<unsigned int, unsigned int>
  Membrane::share(const unsigned int n) const
  {
    const unsigned int size = n_ranks(communicator),
                       rank = this_rank(communicator);
    return {static_cast<unsigned int>(std::uint64_t(n) * rank / size),
            static_cast<unsigned int>(std::uint64_t(n) * (rank + 1) / size)};
  }

  void
  Membrane::share_work(const MPI_Comm comm)
  {
    communicator = comm;
  }

  void
  Membrane::add_cell_terms(const unsigned int       c,
                           const CellTerms<double> &terms,
                           Sums                    &sums) const
  {
    sums.in_plane += terms.in_plane;
    sums.area += terms.area;
    sums.volume += terms.volume;
    for (unsigned int a = 0; a < numbering->cell_nodes[c].size(); ++a)
      {
        const unsigned int i = numbering->cell_nodes[c][a];
        sums.laplacian[i] += terms.laplacian[a];
        sums.normal[i] += terms.normal[a];
        sums.mass[i] += terms.mass[a];
      }
  }

  MembraneEnergy
  Membrane::energy(const Vector<double> &x) const
  {
    Vector<double> no_forces;
    return energy_and_forces(x, no_forces);
  }

  Membrane::Multipliers
  Membrane::energy_derivatives(const Sums &sums, MembraneEnergy &energy) const
  {
    const double kappa = parameters.bending_modulus,
                 c0    = parameters.spontaneous_curvature;
    Multipliers d;
    energy.in_plane = sums.in_plane;
    // The penalties, and their derivatives by the sums A and V. A switched
    // off penalty is left out, so that open test patches (V0 = 0) work.
    if (parameters.area_penalty > 0.)
      {
        energy.area =
          parameters.area_penalty / 2. * std::pow(sums.area - area0, 2) / area0;
        d.area = parameters.area_penalty * (sums.area - area0) / area0;
      }
    if (parameters.volume_penalty > 0.)
      {
        energy.volume = parameters.volume_penalty / 2. *
                        std::pow(sums.volume - volume0, 2) / volume0;
        d.volume =
          parameters.volume_penalty * (sums.volume - volume0) / volume0;
      }

    // The bending energy κ/2 Σ m_i |u_i|², u_i = y_i/m_i - c0 ν_i, and its
    // derivatives by the nodal sums y_i, m_i and w_i = ∫ N_i n dA.
    d.laplacian.resize(numbering->n_nodes);
    d.normal.resize(numbering->n_nodes);
    d.mass.resize(numbering->n_nodes);
    for (unsigned int i = 0; i < numbering->n_nodes; ++i)
      {
        const double       m  = sums.mass[i];
        const double       w  = sums.normal[i].norm();
        const Tensor<1, 3> nu = sums.normal[i] / w;
        const Tensor<1, 3> u  = sums.laplacian[i] / m - c0 * nu;
        energy.bending += kappa / 2. * m * (u * u);
        d.laplacian[i] = kappa * u;
        d.mass[i] = kappa / 2. * (u * u) - kappa * (u * sums.laplacian[i]) / m;
        d.normal[i] = -kappa * c0 * m / w * (u - (u * nu) * nu);
      }
    return d;
  }

  MembraneEnergy
  Membrane::energy_and_forces(const Vector<double> &x,
                              Vector<double>       &forces) const
  {
    MembraneEnergy    energy;
    const Multipliers d = energy_derivatives(sum_shared_cell_terms(x), energy);
    if (forces.size() == 0)
      return energy;

    // F = -dE/dx: per cell, the derivative of its potential φ_c
    // (cell_potential()), whose gradient is E's. φ_c's integrand depends on
    // the DoFs only through the point's position and tangents z = L_q x, so
    // ∂φ_c/∂x = Σ_q L_qᵀ ∂φ_q/∂z, with the 9 derivatives by forward mode:
    // far cheaper than forward mode in the cell's DoFs.
    forces                              = 0.;
    const auto subtract_point_gradients = [&](const auto &law) {
      using ADNumber = Sacado::Fad::SFad<double, 9>;
      Vector<double> values(fe.n_dofs_per_cell()), z(9), dphi_dz(9),
        gradient(fe.n_dofs_per_cell());
      const auto [begin, end] = share(numbering->cell_dofs.size());
      for (unsigned int c = begin; c < end; ++c)
        {
          x.extract_subvector_to(numbering->cell_dofs[c].begin(),
                                 numbering->cell_dofs[c].end(),
                                 values.begin());
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              point_maps[q].vmult(z, values);
              std::array<ADNumber, 9> z_ad;
              for (unsigned int j = 0; j < 9; ++j)
                z_ad[j] = ADNumber(9, j, z[j]);
              const ADNumber phi =
                point_potential(law, c, q, z_ad, point_weights(c, q, d));
              for (unsigned int j = 0; j < 9; ++j)
                dphi_dz[j] = phi.dx(j);
              point_maps[q].Tvmult(gradient, dphi_dz);
              for (unsigned int k = 0; k < gradient.size(); ++k)
                forces[numbering->cell_dofs[c][k]] -= gradient[k];
            }
        }
    };
    std::visit(subtract_point_gradients, elastic_law);
    if (n_ranks(communicator) > 1)
      add_up_over_ranks(make_array_view(forces), communicator);
    return energy;
  }

  template <typename Number>
  Number
  Membrane::cell_potential(const unsigned int       c,
                           const CellTerms<Number> &terms,
                           const Multipliers       &d) const
  {
    Number phi = terms.in_plane + d.area * terms.area + d.volume * terms.volume;
    for (unsigned int a = 0; a < numbering->cell_nodes[c].size(); ++a)
      {
        const unsigned int i = numbering->cell_nodes[c][a];
        phi += d.laplacian[i] * terms.laplacian[a] + d.mass[i] * terms.mass[a] +
               d.normal[i] * terms.normal[a];
      }
    return phi;
  }

  Membrane::PointWeights
  Membrane::point_weights(const unsigned int c,
                          const unsigned int q,
                          const Multipliers &d) const
  {
    PointWeights weights;
    weights.area   = d.area;
    weights.volume = d.volume;
    for (unsigned int a = 0; a < numbering->cell_nodes[c].size(); ++a)
      {
        const unsigned int i = numbering->cell_nodes[c][a];
        weights.mass += d.mass[i] * shape_values(a, q);
        weights.normal += shape_values(a, q) * d.normal[i];
        for (unsigned int alpha = 0; alpha < 2; ++alpha)
          weights.laplacian[alpha] +=
            shape_gradients(a, q)[alpha] * d.laplacian[i];
      }
    return weights;
  }

  std::vector<double>
  Membrane::nodal_areas(const Vector<double> &x) const
  {
    return sum_cell_terms(x).mass;
  }

  Vector<double>
  Membrane::force_densities(const Vector<double> &x,
                            const Vector<double> &f) const
  {
    const std::vector<double> areas = nodal_areas(x);
    Vector<double>            densities(f.size());
    for (unsigned int node = 0; node < numbering->node_dofs.size(); ++node)
      for (const types::global_dof_index i : numbering->node_dofs[node])
        densities[i] = f[i] / areas[node];
    return densities;
  }

  std::vector<Tensor<1, 3>>
  Membrane::nodal_vector_areas(const Vector<double> &x) const
  {
    return sum_cell_terms(x).normal;
  }

  Vector<double>
  Membrane::local_area_changes(const Vector<double> &x) const
  {
    Vector<double> changes(numbering->cell_dofs.size());
    std::visit(
      [&](const auto &law) {
        for (unsigned int c = 0; c < numbering->cell_dofs.size(); ++c)
          changes[c] = cell_terms(law, c, local_positions(c, x)).area /
                         reference_cell_areas[c] -
                       1.;
      },
      elastic_law);
    return changes;
  }

  double
  Membrane::area(const Vector<double> &x) const
  {
    return sum_cell_terms(x).area;
  }

  double
  Membrane::volume(const Vector<double> &x) const
  {
    return sum_cell_terms(x).volume;
  }

  double
  Membrane::reference_area() const
  {
    return area0;
  }

  double
  Membrane::reference_volume() const
  {
    return volume0;
  }

  void
  Membrane::write_vtu(
    const Vector<double>                                      &x,
    const std::string                                         &directory,
    const std::string                                         &name,
    const std::vector<std::pair<std::string, Vector<double>>> &dof_vectors,
    const FieldData                                           &field_data) const
  {
    DataOut<2, 3> data_out;
    build_patches(data_out, x, dof_vectors);
    data_out.set_flags(fast_vtk_flags());
    rbc_ifem::write_vtu(data_out, directory + "/" + name + ".vtu", field_data);
  }

  void
  Membrane::build_patches(
    DataOut<2, 3>                                             &data_out,
    const Vector<double>                                      &x,
    const std::vector<std::pair<std::string, Vector<double>>> &dof_vectors,
    const std::vector<std::pair<std::string, double>> &cell_constants) const
  {
    Vector<double> displacement(x);
    displacement -= reference;
    const MappingFEField<2, 3, Vector<double>> mapping(dof_handler, x);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(3, DataComponentInterpretation::component_is_part_of_vector);
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(displacement,
                             std::vector<std::string>(3, "displacement"),
                             DataOut<2, 3>::type_dof_data,
                             vector_field);
    for (const auto &[field_name, values] : dof_vectors)
      data_out.add_data_vector(values,
                               std::vector<std::string>(3, field_name),
                               DataOut<2, 3>::type_dof_data,
                               vector_field);
    const Vector<double> area_changes = local_area_changes(x);
    data_out.add_data_vector(area_changes,
                             "area_change",
                             DataOut<2, 3>::type_cell_data);
    // The vectors must live until the patches are built.
    std::vector<Vector<double>> constants;
    constants.reserve(cell_constants.size());
    for (const auto &[field_name, value] : cell_constants)
      {
        constants.emplace_back(area_changes.size());
        constants.back() = value;
        data_out.add_data_vector(constants.back(),
                                 field_name,
                                 DataOut<2, 3>::type_cell_data);
      }
    data_out.build_patches(mapping,
                           std::max(2u, parameters.degree),
                           DataOut<2, 3>::curved_inner_cells);
  }

  void
  Membrane::build_surface(const Vector<double> &x,
                          Triangulation<2, 3>  &surface) const
  {
    surface.clear();
    surface.copy_triangulation(dof_handler.get_triangulation());
    surface.reset_all_manifolds();
    surface.set_all_manifold_ids(numbers::flat_manifold_id);
    // The copy has the same cells in the same order; the DoFs of component
    // d at a vertex are the d-th vertex DoFs of the FESystem.
    auto surface_cell = surface.begin_active();
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            surface_cell->vertex(v)[d] = x[cell->vertex_dof_index(v, d)];
        ++surface_cell;
      }
  }
} // namespace rbc_ifem
