#include "knob_library.hpp"

#include <QCoreApplication>
#include <QJsonDocument>
#include <QMetaObject>
#include <QPointer>
#include <QThreadPool>

#include "library_reader.hpp"

namespace knoblab::ui {

KnobLibrary::KnobLibrary(QString db, QObject* parent) : QObject(parent), db_(std::move(db)) {}

void KnobLibrary::refresh() {
  if (loading_) {
    again_ = true;  // one more read once this one is in
    return;
  }
  loading_ = true;
  emit loadingChanged();
  const std::string path = db_.toStdString();
  QPointer<KnobLibrary> self(this);
  QThreadPool::globalInstance()->start([self, path] {
    QVariantList entries;
    QString error;
    try {
      for (const LibraryEntry& e : read_library(path))
        entries.append(QJsonDocument::fromJson(QByteArray::fromStdString(entry_json(e).dump())).toVariant());
    } catch (const std::exception& e) {
      error = QString::fromUtf8(e.what());
    }
    // Back on the UI thread, where the library may be checked for still being there.
    QMetaObject::invokeMethod(
        QCoreApplication::instance(), [self, entries, error] { if (self) self->loaded(entries, error); },
        Qt::QueuedConnection);
  });
}

void KnobLibrary::loaded(const QVariantList& entries, const QString& error) {
  loading_ = false;
  if (error.isEmpty()) {
    entries_ = entries;
    emit entriesChanged();
  } else {
    emit message(error, QStringLiteral("error"));
  }
  emit loadingChanged();
  if (again_) {
    again_ = false;
    refresh();
  }
}

QString KnobLibrary::resultFile(const QString& kind, qint64 id, const QString& name) {
  try {
    return QString::fromStdString(read_result_file(db_.toStdString(), kind.toStdString(), id, name.toStdString()));
  } catch (const std::exception& e) {
    emit message(QString::fromUtf8(e.what()), QStringLiteral("error"));
    return {};
  }
}

QVariantMap KnobLibrary::entry(qint64 captureId) const {
  for (const QVariant& v : entries_) {
    const QVariantMap m = v.toMap();
    if (m.value(QStringLiteral("capture_id")).toLongLong() == captureId) return m;
  }
  return {};
}

}  // namespace knoblab::ui
