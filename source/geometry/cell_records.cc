#include <rbc_ifem/geometry/cell_records.h>

#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <map>
#include <sstream>
#include <stdexcept>

namespace rbc_ifem
{
  namespace
  {
    /// What a rank sends a home rank: records, and the cells whose records
    /// it wants.
    struct Letter
    {
      std::vector<CellId::binary_type> wanted;
      CellRecords                      records;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &wanted &records;
      }
    };

    /**
     * The letters to the home ranks of the cells (a coarse cell's home is
     * its index modulo the ranks): @p records by their cells, and the
     * locally owned cells of @p mesh, whose records are wanted, counted in
     * @p n_owned.
     */
    std::map<unsigned int, Letter>
    letters_home(const CellRecords      &records,
                 const Triangulation<3> &mesh,
                 unsigned int           &n_owned)
    {
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(mesh.get_communicator());
      std::map<unsigned int, Letter> letters;
      const auto letter_to = [&](const CellId &cell) -> Letter & {
        const auto home =
          static_cast<unsigned int>(cell.get_coarse_cell_id() % n_ranks);
        return letters
          .try_emplace(home, Letter{{}, CellRecords(records.values_per_cell())})
          .first->second;
      };
      for (unsigned int i = 0; i < records.size(); ++i)
        letter_to(records.cell(i))
          .records.add(records.cell(i), records.values(i));
      n_owned = 0;
      for (const auto &owned : mesh.active_cell_iterators())
        if (owned->is_locally_owned())
          {
            letter_to(owned->id())
              .wanted.push_back(owned->id().template to_binary<3>());
            ++n_owned;
          }
      return letters;
    }

    /**
     * At a home rank, from the letters @p received by sender: the records
     * each sender asked for, of those that came.
     */
    std::map<unsigned int, CellRecords>
    answer(const std::map<unsigned int, Letter> &received)
    {
      std::map<CellId::binary_type, ArrayView<const double>> held;
      for (const auto &[from, letter] : received)
        for (unsigned int i = 0; i < letter.records.size(); ++i)
          held.emplace(letter.records.cell(i).to_binary<3>(),
                       letter.records.values(i));
      std::map<unsigned int, CellRecords> answers;
      for (const auto &[from, letter] : received)
        for (const auto &wanted : letter.wanted)
          if (const auto found = held.find(wanted); found != held.end())
            answers.try_emplace(from, found->second.size())
              .first->second.add(CellId(wanted), found->second);
      return answers;
    }
  } // namespace

  template <class Archive>
  void
  CellRecords::serialize(Archive &archive, const unsigned int)
  {
    archive &n_values &cells &data;
  }

  CellRecords::CellRecords(const unsigned int values_per_cell)
    : n_values(values_per_cell)
  {}

  void
  CellRecords::add(const CellId &cell, const ArrayView<const double> &values)
  {
    AssertDimension(values.size(), n_values);
    cells.push_back(cell.template to_binary<3>());
    data.insert(data.end(), values.begin(), values.end());
  }

  unsigned int
  CellRecords::size() const
  {
    return cells.size();
  }

  unsigned int
  CellRecords::values_per_cell() const
  {
    return n_values;
  }

  CellId
  CellRecords::cell(const unsigned int i) const
  {
    return CellId(cells[i]);
  }

  ArrayView<const double>
  CellRecords::values(const unsigned int i) const
  {
    return make_array_view(data.begin() + i * n_values,
                           data.begin() + (i + 1) * n_values);
  }

  std::string
  CellRecords::to_bytes() const
  {
    std::ostringstream bytes;
    {
      boost::archive::binary_oarchive archive(bytes);
      archive << *this;
    }
    return bytes.str();
  }

  CellRecords
  CellRecords::from_bytes(const std::string &bytes)
  {
    CellRecords                     records;
    std::istringstream              in(bytes);
    boost::archive::binary_iarchive archive(in);
    archive >> records;
    if (records.data.size() != records.cells.size() * records.n_values)
      throw std::runtime_error("its cell records are damaged");
    return records;
  }

  CellRecords
  CellRecords::to_owners(const Triangulation<3> &mesh) const
  {
    const MPI_Comm communicator = mesh.get_communicator();
    unsigned int   n_owned      = 0;
    const std::map<unsigned int, CellRecords> answers =
      Utilities::MPI::some_to_some(communicator,
                                   answer(Utilities::MPI::some_to_some(
                                     communicator,
                                     letters_home(*this, mesh, n_owned))));
    CellRecords owned(n_values);
    for (const auto &[from, records] : answers)
      {
        owned.n_values = records.n_values;
        owned.cells.insert(owned.cells.end(),
                           records.cells.begin(),
                           records.cells.end());
        owned.data.insert(owned.data.end(),
                          records.data.begin(),
                          records.data.end());
      }
    const auto missing =
      Utilities::MPI::sum(n_owned - owned.size(), communicator);
    if (missing > 0)
      throw std::runtime_error(
        "it holds no values for " + std::to_string(missing) + " of the " +
        std::to_string(mesh.n_global_active_cells()) +
        " cells of the mesh: it was written for another mesh");
    return owned;
  }
} // namespace rbc_ifem
