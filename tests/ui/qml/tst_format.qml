// The numbers and names the screens show (apps/ui/qml/format.mjs).
import QtQuick
import QtTest
import "../../../apps/ui/qml/format.mjs" as Format

TestCase {
    name: "Format"

    function test_rate_data() {
        return [
            { tag: "10 kHz", hz: 10000, text: "10.0 kHz" },
            { tag: "1 kHz", hz: 1000, text: "1.00 kHz" },
            { tag: "500 Hz", hz: 500, text: "500 Hz" },
            { tag: "unknown", hz: 0, text: "–" },
            { tag: "not a number", hz: NaN, text: "–" }
        ];
    }
    function test_rate(data) {
        compare(Format.rate(data.hz), data.text);
    }

    function test_count() {
        compare(Format.count(1234567), "1\u2009234\u2009567");
        compare(Format.count(999), "999");
        compare(Format.count(undefined), "–");
    }

    function test_micros() {
        compare(Format.micros(3.25), "3.3 µs");
        compare(Format.micros(96), "96 µs");
        compare(Format.micros(1020), "1.02 ms");
        compare(Format.micros(undefined), "–");
    }

    function test_age() {
        compare(Format.age(5), "just now");
        compare(Format.age(300), "5 min ago");
        compare(Format.age(3 * 3600 + 5), "3 h ago");
        compare(Format.age(86400), "1 day ago");
        compare(Format.age(5 * 86400), "5 days ago");
        compare(Format.age(-1), "–");
    }

    function test_fault_names_read_as_words_and_unknown_names_pass_through() {
        compare(Format.fault("estop"), "E-stop pressed (or its circuit open)");
        compare(Format.fault("tracking"), "the knob did not follow the sweep");
        compare(Format.fault("new_fault"), "new_fault");
    }

    function test_histogram_bins_are_labelled_from_their_edges() {
        const upper = [1, 2, 4, 2000];
        compare(Format.bin(upper, 0), "< 1.0 µs");
        compare(Format.bin(upper, 2), "2.0–4.0 µs");
        compare(Format.bin(upper, 4), "> 2.00 ms");
    }
}
