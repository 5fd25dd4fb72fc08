#ifndef rbc_ifem_ifem_membrane_series_h
#define rbc_ifem_ifem_membrane_series_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/ifem/parameters.h>
#include <rbc_ifem/ifem/run_record.h>

#include <deal.II/base/mpi.h>

#include <string>

namespace rbc_ifem
{
  /**
   * The membranes of a flowing run at this output, as @p files asks, and
   * the .pvd series that list them, each by a rank that owns cells:
   * per cell, cell_C_SSSS.vtu and cell_C.pvd for every cell C (the records
   * in @p record, which a checkpoint carries); grouped, membranes_SSSS.pvtu
   * and membranes.pvd (SSSS the step). Call it on every rank of
   * @p communicator after the fluid's output of the same step, whose
   * records the grouped series shares: membranes_SSSS.pvtu is written
   * beside every flow_SSSS.pvtu.
   */
  void
  write_membrane_series(const CellPopulation &cells,
                        const MembraneFiles   files,
                        RunRecord            &record,
                        const std::string    &directory,
                        const FieldData      &field_data,
                        const MPI_Comm        communicator);
} // namespace rbc_ifem

#endif
