// Sorting and filtering for the report's tables of class "sortable". The tables are plain HTML and stay
// readable without this script; it only adds a filter box and click-to-sort headers.
document.querySelectorAll('table.sortable').forEach(function (table) {
  var body = table.tBodies[0];
  var filter = document.createElement('input');
  filter.className = 'filter';
  filter.placeholder = 'filter rows (all words must appear)';
  table.parentNode.parentNode.insertBefore(filter, table.parentNode);
  filter.addEventListener('input', function () {
    var words = filter.value.toLowerCase().split(/\s+/).filter(Boolean);
    Array.from(body.rows).forEach(function (row) {
      var text = row.textContent.toLowerCase();
      row.hidden = !words.every(function (w) { return text.indexOf(w) >= 0; });
    });
  });
  Array.from(table.tHead.rows[0].cells).forEach(function (header, column) {
    var ascending = false;
    header.title = 'click to sort';
    header.addEventListener('click', function () {
      ascending = !ascending;
      var key = function (row) {
        var text = row.cells[column].textContent.trim();
        var number = parseFloat(text);
        return isNaN(number) ? text : number;
      };
      var rows = Array.from(body.rows);
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        var order = (typeof x === typeof y) ? (x < y ? -1 : x > y ? 1 : 0) : (typeof x === 'number' ? -1 : 1);
        return ascending ? order : -order;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
