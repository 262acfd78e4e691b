// `tumble inertials`' comparison, as a table and as JSON.
#include "app/robot/inertials_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "app/robot/rewrite.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"
#include "engine/mass/principal_frame.hpp"

namespace tumble::app {
namespace {

const char* format_name(robot::RobotFormat format) {
  switch (format) {
    case robot::RobotFormat::urdf:
      return "urdf";
    case robot::RobotFormat::sdf:
      return "sdf";
    case robot::RobotFormat::mjcf:
      return "mjcf";
  }
  return "";
}

/// "%.6g" of each value, space-separated; values within rounding of zero next to `scale`
/// (the row's largest by default) are written 0, not as -5.8e-20.
std::string numbers(const Eigen::Ref<const Eigen::VectorXd>& values, double scale = 0.0) {
  if (scale == 0.0) scale = values.cwiseAbs().maxCoeff();
  std::string out;
  char buffer[32];
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double value = std::abs(values[i]) <= 1e-12 * scale ? 0.0 : values[i];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    out += (i ? " " : "") + std::string(buffer);
  }
  return out;
}

std::string relative(const std::optional<double>& value, double tolerance, bool check) {
  if (!value) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", *value);
  return std::string(buffer) + (check && *value > tolerance ? "  > tolerance" : "");
}

std::string row(const char* what, const std::string& stated, const std::string& computed,
                const std::string& difference) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "  %-16s %-38s %-38s %s", what, stated.c_str(),
                computed.c_str(), difference.c_str());
  std::string out = buffer;
  out.erase(out.find_last_not_of(' ') + 1);
  return out + "\n";
}

Eigen::Vector3d moments_of(const Eigen::Matrix3d& inertia) {
  return engine::principal_frame(inertia).moments;
}

Eigen::Vector3d off_diagonal(const Eigen::Matrix3d& inertia) {
  return {inertia(0, 1), inertia(0, 2), inertia(1, 2)};
}

/// What is wrong with the stated inertial as a rigid body's, one sentence each.
std::vector<std::string> stated_problems(const std::optional<robot::StatedInertial>& stated) {
  if (!stated) return {"no <inertial> element"};
  std::vector<std::string> out;
  if (!stated->mass) {
    out.push_back("the stated mass is missing");
  } else if (*stated->mass <= 0.0) {
    out.push_back(*stated->mass == 0.0 ? "the stated mass is zero" : "the stated mass is negative");
  }
  if (!stated->inertia) {
    out.push_back("the stated inertia is missing");
  } else if (const auto problem = engine::principal_moments_problem(moments_of(*stated->inertia))) {
    const bool positive = (moments_of(*stated->inertia).array() > 0.0).all();
    out.push_back(std::string(positive ? "the stated inertia is impossible: "
                                       : "the stated inertia is not positive definite: ") +
                  *problem);
  }
  return out;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json matrix_json(const Eigen::Matrix3d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(vector_json(m.row(i).transpose()));
  return rows;
}

nlohmann::json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json link_json(const LinkComparison& link, double tolerance, bool check) {
  nlohmann::json out = {{"name", link.name}, {"geometries", link.geometries}};
  out["stated"] = nullptr;
  if (link.stated) {
    const robot::StatedInertial& s = *link.stated;
    out["stated"] = {{"mass", optional_json(s.mass)},
                     {"center_of_mass", vector_json(s.center_of_mass)},
                     {"inertia", s.inertia ? matrix_json(*s.inertia) : nlohmann::json(nullptr)},
                     {"principal_moments",
                      s.inertia ? vector_json(moments_of(*s.inertia)) : nlohmann::json(nullptr)}};
  }
  out["computed"] = nullptr;
  if (const auto& c = link.result.computed) {
    out["computed"] = {{"mass", c->mass},
                       {"mass_from_density", link.result.mass_from_density},
                       {"mass_from", link.result.mass_from},
                       {"method", robot::methods_text(link.result.methods)},
                       {"methods", link.result.methods},
                       {"center_of_mass", vector_json(c->center_of_mass)},
                       {"inertia", matrix_json(c->inertia)},
                       {"principal_moments", vector_json(moments_of(c->inertia))}};
  }
  out["differences"] = {{"mass", optional_json(link.mass)},
                        {"center_of_mass", optional_json(link.center_of_mass)},
                        {"inertia", optional_json(link.inertia)},
                        {"principal_moments", optional_json(link.moments)}};
  out["problems"] = link.problems;
  out["notes"] = link.notes;
  out["error"] = link.result.error ? nlohmann::json(*link.result.error) : nlohmann::json(nullptr);
  if (check) out["within_tolerance"] = within_tolerance(link, tolerance);
  return out;
}

/// "\ncheck: 2 of 5 links differ by more than 0.001: 'turret', 'hand'\n".
std::string check_summary(const std::vector<LinkComparison>& links, double tolerance) {
  std::string names;
  std::size_t failing = 0;
  for (const LinkComparison& link : links) {
    if (within_tolerance(link, tolerance)) continue;
    names += std::string(failing++ ? ", '" : "'") + link.name + "'";
  }
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", tolerance);
  if (failing == 0) return "\ncheck: every link is within " + std::string(bound) + "\n";
  return "\ncheck: " + std::to_string(failing) + " of " + std::to_string(links.size()) +
         " links differ by more than " + bound + " or cannot be compared: " + names + "\n";
}

/// The whole robot's block of the table.
std::string total_text(const std::optional<robot::RobotTotal>& total, std::size_t links) {
  if (!total) return "\nwhole robot: no link has an inertial to add up\n";
  const engine::MassProperties& p = total->properties;
  std::string out = "\nwhole robot, zero configuration (" + std::to_string(total->counted) +
                    " of " + std::to_string(links) + " links; the model's frame)\n";
  const double size = std::sqrt(p.inertia.trace() / (2.0 * p.mass));
  out += row("mass", numbers(Eigen::Matrix<double, 1, 1>(p.mass)), "", "");
  out += row("centre of mass", numbers(p.center_of_mass, std::max(size, p.center_of_mass.norm())),
             "", "");
  out += row("moments", numbers(moments_of(p.inertia)), "", "");
  out += row("inertia xx yy zz", numbers(p.inertia.diagonal()), "", "");
  out += row("inertia xy xz yz", numbers(off_diagonal(p.inertia), p.inertia.norm()), "", "");
  for (const std::string& name : total->left_out) {
    out += "  note: link '" + name + "' has no inertial to add\n";
  }
  return out;
}

nlohmann::json total_json(const std::optional<robot::RobotTotal>& total) {
  if (!total) return nullptr;
  const engine::MassProperties& p = total->properties;
  return {{"mass", p.mass},
          {"center_of_mass", vector_json(p.center_of_mass)},
          {"inertia", matrix_json(p.inertia)},
          {"principal_moments", vector_json(moments_of(p.inertia))},
          {"links", total->counted},
          {"left_out", total->left_out}};
}

}  // namespace

LinkComparison compare_link(const robot::Link& link, robot::LinkInertial result) {
  LinkComparison out;
  out.name = link.name;
  out.geometries = link.geometries.size();
  out.stated = link.stated;
  out.result = std::move(result);
  out.problems = stated_problems(link.stated);
  out.notes = link.notes;
  out.notes.insert(out.notes.end(), out.result.notes.begin(), out.result.notes.end());
  out.auto_inertial = link.auto_inertial;
  if (link.auto_inertial) out.problems.clear();
  if (!out.result.computed || !link.stated) return out;
  const engine::MassProperties& c = *out.result.computed;
  const robot::StatedInertial& s = *link.stated;
  if (s.mass) out.mass = std::abs(*s.mass - c.mass) / c.mass;
  const double size = std::sqrt(c.inertia.trace() / (2.0 * c.mass));
  out.center_of_mass = (s.center_of_mass - c.center_of_mass).norm() / size;
  if (s.inertia) {
    out.inertia = (*s.inertia - c.inertia).norm() / c.inertia.norm();
    const Eigen::Vector3d moments = moments_of(c.inertia);
    out.moments = (moments_of(*s.inertia) - moments).norm() / moments.norm();
  }
  return out;
}

bool within_tolerance(const LinkComparison& link, double tolerance) {
  if (link.result.error) return false;
  if (!link.result.computed || link.auto_inertial) return true;
  if (!link.problems.empty() || !link.mass || !link.center_of_mass || !link.inertia) return false;
  return *link.mass <= tolerance && *link.center_of_mass <= tolerance && *link.inertia <= tolerance;
}

std::string format_comparison(const robot::Robot& robot, const std::vector<LinkComparison>& links,
                              const std::string& source, double tolerance, bool check,
                              const std::optional<robot::RobotTotal>& total) {
  std::string out = robot.file.string() + " (" + format_name(robot.format) + ", " +
                    std::to_string(links.size()) + " links, geometry from " + source + ")\n";
  for (const LinkComparison& link : links) {
    out += "\nlink '" + link.name + "': " + std::to_string(link.geometries) +
           (link.geometries == 1 ? " geometry\n" : " geometries\n");
    if (link.result.error) {
      out += "  error: " + *link.result.error + "\n";
      continue;
    }
    const auto* s = link.stated ? &*link.stated : nullptr;
    const auto& c = link.result.computed;
    if (c) out += "  inertia method: " + robot::methods_text(link.result.methods) + "\n";
    const std::string from = link.result.mass_from;
    out += row("", "stated",
               c && !from.empty() && from != "stated" ? "computed (" + from + ")" : "computed",
               "relative difference");
    out += row("mass", s && s->mass ? numbers(Eigen::Matrix<double, 1, 1>(*s->mass)) : "-",
               c ? numbers(Eigen::Matrix<double, 1, 1>(c->mass)) : "-",
               relative(link.mass, tolerance, check));
    const double size = c ? std::sqrt(c->inertia.trace() / (2.0 * c->mass)) : 0.0;
    out += row("centre of mass", s ? numbers(s->center_of_mass, size) : "-",
               c ? numbers(c->center_of_mass, std::max(size, c->center_of_mass.norm())) : "-",
               relative(link.center_of_mass, tolerance, check));
    out += row("moments", s && s->inertia ? numbers(moments_of(*s->inertia)) : "-",
               c ? numbers(moments_of(c->inertia)) : "-", relative(link.moments, tolerance, false));
    out += row("inertia xx yy zz", s && s->inertia ? numbers(s->inertia->diagonal()) : "-",
               c ? numbers(c->inertia.diagonal()) : "-", "");
    out += row("inertia xy xz yz",
               s && s->inertia ? numbers(off_diagonal(*s->inertia), s->inertia->norm()) : "-",
               c ? numbers(off_diagonal(c->inertia), c->inertia.norm()) : "-",
               relative(link.inertia, tolerance, check));
    for (const std::string& problem : link.problems) out += "  ! " + problem + "\n";
    for (const std::string& note : link.notes) out += "  note: " + note + "\n";
  }
  out += total_text(total, links.size());
  if (check) out += check_summary(links, tolerance);
  return out;
}

nlohmann::json comparison_to_json(const robot::Robot& robot,
                                  const std::vector<LinkComparison>& links,
                                  const std::string& source, double tolerance, bool check,
                                  const std::optional<robot::RobotTotal>& total) {
  nlohmann::json out = {{"file", robot.file.string()},
                        {"format", format_name(robot.format)},
                        {"from", source},
                        {"links", nlohmann::json::array()}};
  for (const LinkComparison& link : links)
    out["links"].push_back(link_json(link, tolerance, check));
  out["total"] = total_json(total);
  if (check) out["tolerance"] = tolerance;
  return out;
}

robot::PackagePaths package_paths(const std::vector<std::string>& given) {
  robot::PackagePaths out;
  for (const std::string& entry : given) {
    const std::size_t equals = entry.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == entry.size()) {
      throw InputError("--package-path '" + entry + "': expected NAME=DIR");
    }
    out.emplace_back(entry.substr(0, equals), entry.substr(equals + 1));
  }
  return out;
}

namespace {

/// `properties` as -o writes them: a centre-of-mass coordinate or product of inertia within
/// rounding of zero (1e-12 of the link's size or inertia: what summing a mesh's triangles
/// leaves of an exact zero) is written 0, not 9.5e-21.
engine::MassProperties written_inertial(engine::MassProperties properties) {
  const double size = std::sqrt(properties.inertia.trace() / (2.0 * properties.mass));
  for (int i = 0; i < 3; ++i) {
    if (std::abs(properties.center_of_mass[i]) <= 1e-12 * size) properties.center_of_mass[i] = 0;
  }
  const double scale = properties.inertia.norm();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j && std::abs(properties.inertia(i, j)) <= 1e-12 * scale) {
        properties.inertia(i, j) = 0;
      }
    }
  }
  return properties;
}

/// Writes `text` to `output` whole or not at all: a temporary sibling renamed into place.
void write_atomically(const std::filesystem::path& output, const std::filesystem::path& input,
                      const std::string& text) {
  const std::filesystem::path target = checked_output(output, {input});
  remove_stale_temporaries(target);
  const std::filesystem::path temporary = temporary_sibling(target);
  try {
    write_text_file(temporary, text);
    std::filesystem::rename(temporary, target);
  } catch (const std::filesystem::filesystem_error& error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError("cannot write '" + output.string() + "': " + error.code().message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace

bool InertialsReport::failed() const {
  for (const LinkComparison& link : links) {
    if (link.result.error) return true;
  }
  return false;
}

std::vector<std::string> InertialsReport::errors() const {
  std::vector<std::string> out;
  for (const LinkComparison& link : links) {
    if (link.result.error) out.push_back(robot.file.string() + ": " + *link.result.error);
  }
  return out;
}

InertialsReport compute_inertials(const std::filesystem::path& file, const robot::ReadOptions& read,
                                  const robot::ComputeOptions& compute) {
  InertialsReport report{robot::read_robot(file, read),
                         {},
                         read.from == robot::GeometrySource::collision ? "collision" : "visual",
                         std::nullopt};
  robot::check_link_options(report.robot, compute);
  std::vector<robot::LinkInertial> results;
  for (const robot::Link& link : report.robot.links) {
    results.push_back(robot::compute_link_inertial(link, compute, report.robot.format));
  }
  robot::spread_total_mass(report.robot.links, results, compute);
  for (std::size_t i = 0; i < results.size(); ++i) {
    report.links.push_back(compare_link(report.robot.links[i], std::move(results[i])));
  }
  report.total = robot::robot_total(report.robot.links, final_inertials(report.links));
  return report;
}

std::vector<std::optional<engine::MassProperties>> final_inertials(
    const std::vector<LinkComparison>& links) {
  std::vector<std::optional<engine::MassProperties>> out;
  for (const LinkComparison& link : links) {
    std::optional<engine::MassProperties> inertial = link.result.computed;
    const auto& s = link.stated;
    if (!inertial && !link.result.error && s && s->mass && *s->mass > 0.0 && s->inertia) {
      inertial = engine::MassProperties{*s->mass, s->center_of_mass, *s->inertia};
    }
    out.push_back(inertial);
  }
  return out;
}

InertialsReport inertials_report(const InertialsOptions& options) {
  robot::ReadOptions read;
  read.from = options.from;
  read.packages = package_paths(options.package_paths);
  return compute_inertials(options.robot, read, options.compute);
}

std::string rewritten_inertials(const InertialsReport& report, robot::InertialFrame frame) {
  std::vector<std::optional<engine::MassProperties>> inertials;
  std::vector<std::string> comments;
  for (const LinkComparison& link : report.links) {
    inertials.push_back(link.result.computed
                            ? std::optional(written_inertial(*link.result.computed))
                            : std::nullopt);
    comments.push_back("inertial computed by tumble from the " + report.source +
                       " geometry; inertia method: " + robot::methods_text(link.result.methods));
  }
  return robot::rewritten_text(report.robot, inertials, frame, comments);
}

void write_inertials(const InertialsReport& report, const std::filesystem::path& output,
                     robot::InertialFrame frame) {
  const std::vector<std::string> errors = report.errors();
  if (!errors.empty()) {
    throw InputError(errors.front() + "; nothing written to '" + output.string() + "'");
  }
  write_atomically(output, report.robot.file, rewritten_inertials(report, frame));
}

int write_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err) {
  // A refused output fails before any work (and checked again when written).
  if (options.output) checked_output(*options.output, {options.robot});
  const InertialsReport report = inertials_report(options);
  for (const LinkComparison& link : report.links) {
    if (link.result.error) {
      err << "tumble inertials: error: " << report.robot.file.string() << ": " << *link.result.error
          << "\n";
    }
  }
  if (options.json) {
    out << comparison_to_json(report.robot, report.links, report.source, options.tolerance,
                              options.check, report.total)
               .dump(2)
        << "\n";
  } else {
    out << format_comparison(report.robot, report.links, report.source, options.tolerance,
                             options.check, report.total);
  }
  if (report.failed()) {
    if (options.output) {
      err << "tumble inertials: nothing written to '" << options.output->string()
          << "': a link failed\n";
    }
    return kExitInputError;
  }
  if (options.output) write_inertials(report, *options.output, options.frame);
  if (options.check) {
    for (const LinkComparison& link : report.links) {
      if (!within_tolerance(link, options.tolerance)) return kExitCheckFailed;
    }
  }
  return kExitDone;
}

}  // namespace tumble::app
