// The knob library for QML: the store's captures with their latest fit and
// discrepancy result (library_reader.hpp), read off the UI thread whenever
// refresh() is asked for (after a capture, a fit, a discrepancy run).
#pragma once

#include <QObject>
#include <QString>
#include <QVariantList>
#include <QtQml/qqmlregistration.h>

namespace knoblab::ui {

class KnobLibrary : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one library")
  Q_PROPERTY(QString db READ db CONSTANT)
  // Newest first; each a map as library_reader.hpp's entry_json gives it.
  Q_PROPERTY(QVariantList entries READ entries NOTIFY entriesChanged)
  Q_PROPERTY(bool loading READ loading NOTIFY loadingChanged)

 public:
  explicit KnobLibrary(QString db, QObject* parent = nullptr);

  QString db() const { return db_; }
  QVariantList entries() const { return entries_; }
  bool loading() const { return loading_; }

  Q_INVOKABLE void refresh();
  // The entry of a capture ({} when it is not in the library).
  Q_INVOKABLE QVariantMap entry(qint64 captureId) const;
  // A file stored with a result ("fit" or "discrepancy", its id), e.g. a
  // report figure's CSV; "" when there is none (a message says why when the
  // store could not be read).
  Q_INVOKABLE QString resultFile(const QString& kind, qint64 id, const QString& name);

 signals:
  void entriesChanged();
  void loadingChanged();
  void message(const QString& text, const QString& level);

 private:
  void loaded(const QVariantList& entries, const QString& error);

  QString db_;
  QVariantList entries_;
  bool loading_ = false, again_ = false;
};

}  // namespace knoblab::ui
