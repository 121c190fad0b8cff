#include "design_session.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <system_error>

#include "daemon_link.hpp"
#include "design_variant.hpp"
#include "knoblab/design/curve.hpp"
#include "knoblab/design/design_json.hpp"
#include "knoblab/design/edits.hpp"
#include "knoblab/design/render_tiles.hpp"
#include "knoblab/design/templates.hpp"
#include "knoblab/jsonread/json_reader.hpp"
#include "pane_snap.hpp"
#include "stability_bound.hpp"

namespace knoblab::ui {

namespace fs = std::filesystem;
using design::Channel;
using design::Design;
using design::TileRef;

namespace {

const QString kWarning = QStringLiteral("warning");
const QString kInfo = QStringLiteral("info");
const QString kError = QStringLiteral("error");

std::size_t at(int i) { return i < 0 ? static_cast<std::size_t>(-1) : static_cast<std::size_t>(i); }

// A tile's own length on a channel's axis, where it has one: a tile drawn
// over θ placed on a θ channel (stretched), or over t in time; otherwise a
// quarter turn, or 1 s, for the designer to resize.
double dropped_length(const design::Tile& t, Channel c) {
  const bool time = c == Channel::Time;
  const bool drawn_over_angle = t.drawn_for == Channel::Position || t.drawn_for == Channel::Acceleration;
  if (design::stretched(c) && (time ? t.drawn_for == Channel::Time : drawn_over_angle))
    return t.waveform.x_max() - t.waveform.x_min();
  return time ? 1.0 : std::numbers::pi / 2;
}

const design::Tile& palette_tile(const Design& d, int tab, int index) {
  if (tab < 0 || at(tab) >= d.palette.size()) throw design::EditError("There is no such palette tab.");
  const auto& tiles = d.palette[at(tab)].tiles;
  if (index < 0 || at(index) >= tiles.size()) throw design::EditError("There is no such tile in the palette.");
  return tiles[at(index)];
}

const design::PlacedTile& placed(const Design& d, const TileRef& r) {
  const auto& lines = d.lines(r.channel).lines;
  if (r.line >= lines.size() || r.index >= lines[r.line].tiles.size())
    throw design::EditError("There is no such tile in the pane.");
  return lines[r.line].tiles[r.index];
}

// "tile 1", "tile 2", … : the first not in the tab.
std::string free_tile_name(const Design& d, int tab) {
  if (tab < 0 || at(tab) >= d.palette.size()) return "tile 1";
  for (int n = 1;; ++n) {
    const std::string name = "tile " + std::to_string(n);
    const auto& tiles = d.palette[at(tab)].tiles;
    if (std::none_of(tiles.begin(), tiles.end(), [&](const design::Tile& t) { return t.name == name; })) return name;
  }
}

}  // namespace

DesignSession::DesignSession(DaemonLink* link, Options options, QObject* parent)
    : QObject(parent),
      link_(link),
      dir_(options.designsDir.toStdString()),
      history_(design::new_design("untitled")),
      player_(link) {
  history_.mark_saved();  // nothing to save until the designer changes something
  connect(&player_, &DesignPlayer::playingChanged, this, &DesignSession::playingChanged);
  connect(&player_, &DesignPlayer::message, this, &DesignSession::message);
  connect(link_, &DaemonLink::stateChanged, this, &DesignSession::read_limits);
  changed();
  refreshFiles();
}

QString DesignSession::editorChannel() const {
  const auto n = design::channel_name(design().editor.drawn_for);
  return QString::fromUtf8(n.data(), static_cast<qsizetype>(n.size()));
}

QVariantList DesignSession::editorCurve(double from, double to, int samples) const {
  return curve_variant(design().editor.waveform, from, to, samples);
}

template <class Edit>
bool DesignSession::edit(const QString& label, Edit&& e) {
  try {
    history_.apply(label.toStdString(), std::forward<Edit>(e));
  } catch (const design::EditError& error) {
    emit message(QString::fromStdString(error.what()), kWarning);
    return false;
  } catch (const std::invalid_argument& error) {  // a channel name the screen got wrong
    emit message(QString::fromStdString(error.what()), kError);
    return false;
  }
  changed();
  return true;
}

void DesignSession::changed() {
  const Design& d = design();
  editor_points_ = points_variant(d.editor.waveform);
  palette_ = palette_variant(d);
  channels_ = channels_variant(d);
  ++revision_;
  emit designChanged();
  // hapticd cross-fades to the new set: what changes is felt at once.
  if (player_.playing()) player_.update(design::load_tiles_args(d));
}

bool DesignSession::editTile(int tab, int index) {
  return edit(QStringLiteral("tile into the editor"), [&](Design& d) { design::edit_tile(d, at(tab), at(index)); });
}

bool DesignSession::movePoint(int index, double x, double y) {
  return edit(QStringLiteral("moved point %1").arg(index + 1),
              [&](Design& d) { design::move_point(d, at(index), {x, y}); });
}

bool DesignSession::addPoint(double x, double y) {
  return edit(QStringLiteral("added a point"), [&](Design& d) { design::add_point(d, {x, y}); });
}

bool DesignSession::removePoint(int index) {
  return edit(QStringLiteral("removed point %1").arg(index + 1),
              [&](Design& d) { design::remove_point(d, at(index)); });
}

bool DesignSession::scaleSelection(double from, double to, bool horizontal, double at_, double factor) {
  return edit(QStringLiteral("scaled the selection ×%1").arg(factor), [&](Design& d) {
    design::scale_selection(d, {from, to}, horizontal ? design::Mirror::Horizontal : design::Mirror::Vertical, at_,
                            factor);
  });
}

bool DesignSession::tileFromSelection(double from, double to, int tab, const QString& name) {
  const std::string tile_name = name.isEmpty() ? free_tile_name(design(), tab) : name.toStdString();
  return edit(QStringLiteral("made a tile"), [&](Design& d) {
    design::add_tile(d, at(tab), design::tile_from_selection(d, {from, to}, tile_name));
  });
}

bool DesignSession::addTab(const QString& name) {
  return edit(QStringLiteral("added a tab"), [&](Design& d) { design::add_tab(d, name.toStdString()); });
}

bool DesignSession::renameTab(int tab, const QString& name) {
  return edit(QStringLiteral("renamed a tab"), [&](Design& d) { design::rename_tab(d, at(tab), name.toStdString()); });
}

bool DesignSession::removeTab(int tab) {
  return edit(QStringLiteral("removed a tab"), [&](Design& d) { design::remove_tab(d, at(tab)); });
}

bool DesignSession::renameTile(int tab, int index, const QString& name) {
  return edit(QStringLiteral("renamed a tile"),
              [&](Design& d) { design::rename_tile(d, at(tab), at(index), name.toStdString()); });
}

bool DesignSession::removeTile(int tab, int index) {
  return edit(QStringLiteral("removed a tile"), [&](Design& d) { design::remove_tile(d, at(tab), at(index)); });
}

bool DesignSession::placeTile(const QString& channel, int line, int tab, int index, double from, double snap) {
  return edit(QStringLiteral("placed a tile"), [&](Design& d) {
    const Channel c = channel_of(channel);
    const design::Tile t = palette_tile(d, tab, index);
    const PaneSpan s = design::stretched(c) ? snap_span(from, dropped_length(t, c), pane_edges(d, c), snap)
                                            : fill_gap(from, pane_edges(d, c), dropped_length(t, c));
    design::place_tile(d, c, at(line), t, s.from, s.to);
  });
}

bool DesignSession::placeTileAt(const QString& channel, int line, int tab, int index, double from, double to) {
  return edit(QStringLiteral("placed a tile"), [&](Design& d) {
    design::place_tile(d, channel_of(channel), at(line), palette_tile(d, tab, index), from, to);
  });
}

bool DesignSession::moveTile(const QString& channel, int line, int index, double from, double snap) {
  return edit(QStringLiteral("moved a tile"), [&](Design& d) {
    const TileRef r{channel_of(channel), at(line), at(index)};
    const design::PlacedTile& p = placed(d, r);
    const PaneSpan s = snap_span(from, p.to - p.from, pane_edges(d, r.channel, std::pair{r.line, r.index}), snap);
    // resize_tile, not move_tile: move_tile recomputes the end as start +
    // length, a rounding away from the edge the end snapped onto.
    design::resize_tile(d, r, s.from, s.to);
  });
}

bool DesignSession::resizeTileEnd(const QString& channel, int line, int index, const QString& end, double at_,
                                  double snap) {
  return edit(QStringLiteral("resized a tile"), [&](Design& d) {
    const TileRef r{channel_of(channel), at(line), at(index)};
    const design::PlacedTile p = placed(d, r);
    const double edge = snap_edge(at_, pane_edges(d, r.channel, std::pair{r.line, r.index}), snap);
    if (end == QStringLiteral("from")) design::resize_tile(d, r, edge, p.to);
    else design::resize_tile(d, r, p.from, edge);
  });
}

bool DesignSession::resizeTile(const QString& channel, int line, int index, double from, double to) {
  return edit(QStringLiteral("resized a tile"),
              [&](Design& d) { design::resize_tile(d, {channel_of(channel), at(line), at(index)}, from, to); });
}

bool DesignSession::removePlaced(const QString& channel, int line, int index) {
  return edit(QStringLiteral("removed a placed tile"),
              [&](Design& d) { design::remove_placed(d, {channel_of(channel), at(line), at(index)}); });
}

bool DesignSession::superimpose(const QString& channel, int lineA, int indexA, int lineB, int indexB) {
  return edit(QStringLiteral("superimposed two tiles"), [&](Design& d) {
    const Channel c = channel_of(channel);
    design::superimpose(d, {c, at(lineA), at(indexA)}, {c, at(lineB), at(indexB)});
  });
}

bool DesignSession::addLine(const QString& channel) {
  return edit(QStringLiteral("added a line"), [&](Design& d) { design::add_line(d, channel_of(channel)); });
}

bool DesignSession::removeLine(const QString& channel, int line) {
  return edit(QStringLiteral("removed a line"),
              [&](Design& d) { design::remove_line(d, channel_of(channel), at(line)); });
}

bool DesignSession::setLineActive(const QString& channel, int line, bool active) {
  return edit(active ? QStringLiteral("line on") : QStringLiteral("line off"),
              [&](Design& d) { design::set_line_active(d, channel_of(channel), at(line), active); });
}

bool DesignSession::setChannelPlay(const QString& channel, bool play) {
  return edit(play ? QStringLiteral("%1 plays").arg(channel) : QStringLiteral("%1 silent").arg(channel),
              [&](Design& d) { design::set_channel_play(d, channel_of(channel), play); });
}

bool DesignSession::setTimeLoop(bool loop) {
  return edit(loop ? QStringLiteral("time loops") : QStringLiteral("time once"),
              [&](Design& d) { design::set_time_loop(d, loop); });
}

bool DesignSession::renameDesign(const QString& name) {
  return edit(QStringLiteral("renamed the design"), [&](Design& d) { design::rename_design(d, name.toStdString()); });
}

void DesignSession::undo() {
  const std::string label = history_.undo();
  if (label.empty()) return;
  changed();
  emit message(QStringLiteral("Undone: ") + QString::fromStdString(label), kInfo);
}

void DesignSession::redo() {
  const std::string label = history_.redo();
  if (label.empty()) return;
  changed();
  emit message(QStringLiteral("Redone: ") + QString::fromStdString(label), kInfo);
}

void DesignSession::newDesign(const QString& name) {
  if (!edit(QStringLiteral("new design"), [&](Design& d) { d = design::new_design(name.toStdString()); })) return;
  file_.clear();
  emit fileChanged();
}

fs::path DesignSession::resolve(const QString& path) const {
  fs::path p = path.toStdString();
  if (p.is_relative() && !p.has_parent_path()) p = dir_ / p;
  if (!p.has_extension()) p += ".json";
  return p;
}

bool DesignSession::open(const QString& path, bool announce) {
  const fs::path file = resolve(path);
  Design d;
  try {
    d = design::read_design(file);
  } catch (const std::exception& e) {  // jsonread::PathError: the file, the key and why
    emit message(QString::fromStdString(e.what()), kError);
    return false;
  }
  history_.reset(std::move(d));
  file_ = file;
  emit fileChanged();
  changed();
  if (announce) emit message(QStringLiteral("Opened ") + fileName(), kInfo);
  return true;
}

bool DesignSession::save(const QString& path) {
  const fs::path file = !path.isEmpty()    ? resolve(path)
                        : !file_.empty()   ? file_
                                           : resolve(QString::fromStdString(design().name).replace(' ', '-'));
  try {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    design::write_design(file, design());
  } catch (const std::exception& e) {
    emit message(QStringLiteral("Not saved: ") + QString::fromStdString(e.what()), kError);
    return false;
  }
  history_.mark_saved();
  file_ = file;
  emit fileChanged();
  emit designChanged();  // modified
  refreshFiles();
  emit message(QStringLiteral("Saved ") + fileName() + QStringLiteral(" in ") + designsDir(), kInfo);
  return true;
}

void DesignSession::refreshFiles() {
  QStringList files;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec))
    if (e.is_regular_file() && e.path().extension() == ".json") files << QString::fromStdString(e.path().filename().string());
  files.sort();
  if (files == files_) return;
  files_ = files;
  emit filesChanged();
}

void DesignSession::play() {
  try {
    player_.play(design::load_tiles_args(design()));
  } catch (const std::exception& e) {
    emit message(QStringLiteral("The design cannot be played: ") + QString::fromStdString(e.what()), kWarning);
  }
}

void DesignSession::stop() { player_.stop(); }

void DesignSession::read_limits() {
  const QVariant limit = link_->state().value(QStringLiteral("torque_limit_Nm"));
  const double value = limit.isValid() && limit.toDouble() > 0.0 ? limit.toDouble() : 0.18;
  const double rate = link_->state().value(QStringLiteral("rate_hz")).toDouble();
  if (value == torque_limit_ && rate == rate_hz_) return;
  torque_limit_ = value;
  if (rate != rate_hz_ && rate > 0.0) {
    // Once per rate: the bound takes a few bisections of the loop's roots.
    try {
      const StabilityBound b = stability_bound(rate);
      max_damping_ = b.max_damping;
      max_stiffness_ = b.max_stiffness;
    } catch (const std::exception&) {
      max_damping_ = max_stiffness_ = std::numeric_limits<double>::quiet_NaN();
    }
  }
  rate_hz_ = rate;
  emit limitsChanged();
}

}  // namespace knoblab::ui
