#include <rbc_ifem/base/input_files.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_text.h>

#include <deal.II/base/utilities.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// Set "Subsection/.../Entry" of @p prm to @p value.
    void
    set_entry(ParameterHandler  &prm,
              const std::string &path,
              const std::string &value)
    {
      std::vector<std::string> names = Utilities::split_string_list(path, '/');
      const std::string        entry = names.back();
      names.pop_back();
      for (const std::string &subsection : names)
        prm.enter_subsection(subsection);
      prm.set(entry, value);
      for (std::size_t i = 0; i < names.size(); ++i)
        prm.leave_subsection();
    }

    /// The whole content of the file @p path.
    std::string
    file_bytes(const std::string &path)
    {
      std::ifstream in(path, std::ios::binary);
      if (!in)
        throw OutputError(path, "it cannot be read to copy it");
      std::ostringstream bytes;
      bytes << in.rdbuf();
      return bytes.str();
    }
  } // namespace

  void
  resolve_file_parameters(ParameterHandler &prm, const std::string &folder)
  {
    if (folder.empty())
      return;
    const auto values = parameter_values(parameter_text(prm));
    for (const auto &[path, pattern] : parameter_patterns(prm))
      if (pattern.rfind("[FileName", 0) == 0)
        {
          const std::string &value = values.at(path);
          if (!value.empty() && std::filesystem::path(value).is_relative())
            set_entry(prm,
                      path,
                      (std::filesystem::path(folder) / value)
                        .lexically_normal()
                        .string());
        }
  }

  std::string
  copy_name(const InputFile &input)
  {
    return "inputs/" + std::filesystem::path(input.path).filename().string();
  }

  std::string
  with_input_copies(const std::string            &text,
                    const std::vector<InputFile> &inputs)
  {
    static const std::regex  set_line(R"((\s*set (.*?)\s*= ).*)");
    static const std::regex  subsection_line(R"(\s*subsection (.*?)\s*)");
    static const std::regex  end_line(R"(\s*end\s*)");
    std::istringstream       lines(text);
    std::string              line, result;
    std::vector<std::string> subsections;
    while (std::getline(lines, line))
      {
        std::smatch m;
        if (std::regex_match(line, m, set_line))
          {
            std::string path;
            for (const std::string &subsection : subsections)
              path += subsection + '/';
            for (const InputFile &input : inputs)
              if (input.entry == path + m[2].str())
                line = m[1].str() + copy_name(input);
          }
        else if (std::regex_match(line, m, subsection_line))
          subsections.push_back(m[1]);
        else if (std::regex_match(line, end_line) && !subsections.empty())
          subsections.pop_back();
        result += line + '\n';
      }
    return result;
  }

  void
  copy_input_files(const std::vector<InputFile> &inputs,
                   const std::string            &directory,
                   const bool                    keep_existing,
                   const MPI_Comm                communicator)
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    for (const InputFile &input : inputs)
      {
        const std::string copy = directory + "/" + copy_name(input);
        std::error_code   error;
        if (std::filesystem::equivalent(input.path, copy, error) ||
            (keep_existing && std::filesystem::exists(copy)))
          continue;
        std::filesystem::create_directories(directory + "/inputs", error);
        write_text_atomically(copy, file_bytes(input.path));
      }
  }
} // namespace rbc_ifem
