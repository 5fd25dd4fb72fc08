#ifndef rbc_ifem_diffusion_side_field_h
#define rbc_ifem_diffusion_side_field_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <functional>
#include <string>
#include <utility>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * One side's field of a cut-cell problem for the output: on each mesh
   * cell the component that @p field_on gives (numbers::invalid_unsigned_int:
   * 0, the mesh cell is wholly on the other side). A problem with a field
   * per colour of red cells writes each kind of field as one.
   */
  class SideField : public DataPostprocessorScalar<3>
  {
  public:
    SideField(const std::string &name,
              std::function<unsigned int(const DoFHandler<3>::cell_iterator &)>
                field_on)
      : DataPostprocessorScalar<3>(name, update_values)
      , field_on(std::move(field_on))
    {}

    void
    evaluate_vector_field(const DataPostprocessorInputs::Vector<3> &inputs,
                          std::vector<Vector<double>> &computed) const override
    {
      const unsigned int field = field_on(inputs.template get_cell<3>());
      for (unsigned int q = 0; q < computed.size(); ++q)
        computed[q](0) = field == numbers::invalid_unsigned_int ?
                           0. :
                           inputs.solution_values[q](field);
    }

  private:
    const std::function<unsigned int(const DoFHandler<3>::cell_iterator &)>
      field_on;
  };
} // namespace rbc_ifem

#endif
